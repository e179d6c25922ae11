//! The packet renderer's gather of hit records into structure-of-arrays globals
//! (`gather_globals_read`, register transposes for 4, 8 and 16 lanes) against the records
//! read field by field, for every width, plain and dual, and subsets of the globals.

use anysl_ad::Dual;
use anysl_core::{GlobalSet, Globals, ShadingFloat, Vec3};
use anysl_renderers::scene::SurfaceHit;
use anysl_renderers::shading::{gather_globals_read, MAX_LANES};
use anysl_simd::{F32x16, F32x4, F32x8};
use glam::Vec3A;

/// Hit `l` with every float distinct (lane and field both recoverable from the value).
fn hit(l: usize) -> SurfaceHit {
    let k = std::cell::Cell::new(0.0f32);
    let next = || {
        k.set(k.get() + 1.0);
        l as f32 * 1000.0 + k.get() + 0.25
    };
    let v3 = || Vec3A::new(next(), next(), next());
    SurfaceHit {
        p: v3(),
        n: v3(),
        ng: v3(),
        i: v3(),
        e: v3(),
        s: next(),
        t: next(),
        du: next(),
        dv: next(),
        dpdu: v3(),
        dpdv: v3(),
        dpdx: v3(),
        dpdy: v3(),
        dndx: v3(),
        dndy: v3(),
        dsdx: next(),
        dsdy: next(),
        dtdx: next(),
        dtdy: next(),
        u: next(),
        v: next(),
        cs: [next(), next(), next()],
        os: [next(), next(), next()],
        surface: l as u32,
    }
}

fn check<F: ShadingFloat>(group: u32, read: GlobalSet) {
    let hits: Vec<SurfaceHit> = (0..MAX_LANES).map(hit).collect();
    let first = group.trailing_zeros() as usize;
    let g: Globals<F> = gather_globals_read::<F>(&hits, group, first, read);
    let has = |x: GlobalSet| read.0 & x.0 != 0;
    for lane in 0..F::LANES {
        let h = &hits[if (group >> lane) & 1 != 0 { lane } else { first }];
        let want3 = |on: bool, v: Vec3A| if on { [v.x, v.y, v.z] } else { [0.0; 3] };
        let got3 = |v: &Vec3<F>| [v.x, v.y, v.z].map(|c| c.lane(lane) as f32);
        let d3 = |v: &Vec3<F>, y: bool| [v.x, v.y, v.z].map(|c| if y { c.dy() } else { c.dx() }.lane(lane) as f32);
        let what = format!("{} group {group:#x} read {:#x} lane {lane}", F::NAME, read.0);
        assert_eq!(got3(&g.P), want3(has(GlobalSet::P), h.p), "P {what}");
        assert_eq!(got3(&g.N), want3(has(GlobalSet::N), h.n), "N {what}");
        assert_eq!(got3(&g.Ng), want3(has(GlobalSet::NG), h.ng), "Ng {what}");
        assert_eq!(got3(&g.I), want3(has(GlobalSet::I), h.i), "I {what}");
        assert_eq!(got3(&g.E), want3(has(GlobalSet::E), h.e), "E {what}");
        assert_eq!(got3(&g.dPdu), want3(has(GlobalSet::DPDU), h.dpdu), "dPdu {what}");
        assert_eq!(got3(&g.dPdv), want3(has(GlobalSet::DPDV), h.dpdv), "dPdv {what}");
        let on = |x: GlobalSet, v: f32| if has(x) { v } else { 0.0 };
        assert_eq!(g.s.lane(lane) as f32, on(GlobalSet::S, h.s), "s {what}");
        assert_eq!(g.t.lane(lane) as f32, on(GlobalSet::T, h.t), "t {what}");
        assert_eq!(g.u.lane(lane) as f32, on(GlobalSet::U, h.u), "u {what}");
        assert_eq!(g.v.lane(lane) as f32, on(GlobalSet::V, h.v), "v {what}");
        let white = |x: GlobalSet, c: [f32; 3]| if has(x) { c } else { [1.0; 3] };
        let rgb = |c: &anysl_core::Color<F>| [c.r, c.g, c.b].map(|x| x.lane(lane) as f32);
        assert_eq!(rgb(&g.Cs), white(GlobalSet::CS, h.cs), "Cs {what}");
        assert_eq!(rgb(&g.Os), white(GlobalSet::OS, h.os), "Os {what}");
        assert_eq!(g.du.lane(lane) as f32, on(GlobalSet::DU, h.du), "du {what}");
        assert_eq!(g.dv.lane(lane) as f32, on(GlobalSet::DV, h.dv), "dv {what}");
        if F::HAS_DERIVS && has(GlobalSet::P) && has(GlobalSet::N) && has(GlobalSet::S) && has(GlobalSet::T) {
            assert_eq!(d3(&g.P, false), [h.dpdx.x, h.dpdx.y, h.dpdx.z], "dP/dx {what}");
            assert_eq!(d3(&g.P, true), [h.dpdy.x, h.dpdy.y, h.dpdy.z], "dP/dy {what}");
            assert_eq!(d3(&g.N, false), [h.dndx.x, h.dndx.y, h.dndx.z], "dN/dx {what}");
            assert_eq!(d3(&g.N, true), [h.dndy.x, h.dndy.y, h.dndy.z], "dN/dy {what}");
            assert_eq!(
                [g.s.dx(), g.s.dy(), g.t.dx(), g.t.dy()].map(|c| c.lane(lane) as f32),
                [h.dsdx, h.dsdy, h.dtdx, h.dtdy]
            );
        }
    }
}

fn all_widths(group: u32, read: GlobalSet) {
    check::<f32>(group & 1 | 1, read);
    check::<Dual<f32>>(group & 1 | 1, read);
    check::<F32x4>(group & 0xf, read);
    check::<F32x8>(group & 0xff, read);
    check::<Dual<F32x8>>(group & 0xff, read);
    check::<F32x16>(group, read);
}

#[test]
fn gathered_globals_are_the_hit_records_fields() {
    let reads = [
        GlobalSet::ALL,
        GlobalSet::P.union(GlobalSet::N).union(GlobalSet::I).union(GlobalSet::S).union(GlobalSet::T),
        GlobalSet::DU.union(GlobalSet::DV).union(GlobalSet::DPDV),
        GlobalSet::NG.union(GlobalSet::E).union(GlobalSet::U).union(GlobalSet::DPDU),
    ];
    for read in reads {
        // All lanes, alternating lanes (the others read lane `first`), lanes from 3 on.
        for group in [0xffff, 0x5555, 0xaaaa, 0xfff8] {
            all_widths(group, read);
        }
    }
}
