//! `parquet` — wooden planks in a basket-weave parquet on (s, t), each with its own grain.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// Basket-weave parquet on (s, t): square tiles of `tilesize`, each holding `planks`
    /// planks, the plank direction alternating between s and t from tile to tile like a
    /// checkerboard. Every plank is its own piece of wood: growth rings (smoothstep profile,
    /// as in `wood`) around an axis along the plank, placed by the plank's `vcellnoise`
    /// beside and below it and perturbed by two octaves of noise, plus fine grain along the
    /// plank and a per-plank tint (`±plankvary/2`). Grooves of `groovewidth` (a fraction of
    /// the plank width) run around every plank, box-filtered with `filterstep`; plastic
    /// lighting with the highlight suppressed in the grooves, `Oi = Os`.
    pub struct Parquet: surface "parquet" uses_derivatives = true {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.75;
        /// Specular coefficient.
        uniform float Ks = 0.15;
        /// Highlight roughness.
        uniform float roughness = 0.1;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
        /// Side of a basket-weave tile in (s, t).
        uniform float tilesize = 0.25;
        /// Planks per tile (rounded, at least 1).
        uniform float planks = 3.0;
        /// Width of the grooves, as a fraction of the plank width.
        uniform float groovewidth = 0.05;
        /// Growth rings per plank width.
        uniform float ringscale = 6.0;
        /// Strength of the noise perturbing the rings, in rings.
        uniform float ringnoise = 0.6;
        /// Frequency of the grain across the plank, per plank width.
        uniform float grainscale = 40.0;
        /// Relative colour variation between planks.
        uniform float plankvary = 0.25;
        /// Colour between the rings.
        uniform color lightwood = [0.76, 0.52, 0.29];
        /// Colour of the rings.
        uniform color darkwood = [0.45, 0.26, 0.11];
        /// Colour of the grooves.
        uniform color groovecolor = [0.08, 0.05, 0.03];
    }
}

impl Parquet {
    /// The parquet at (s, t): `(in_plank, wood_colour)` with `in_plank` in [0, 1] (0 in a
    /// groove, filtered at the groove edges).
    #[inline(always)]
    #[must_use]
    pub fn pattern<F: ShadingFloat>(&self, s: F, t: F) -> (F, Color<F>) {
        let (zero, half, one) = (F::c(0.0), F::c(0.5), F::c(1.0));
        let nplanks = self.planks.round().max(1.0);
        let ss = s / F::c(self.tilesize);
        let tt = t / F::c(self.tilesize);
        let (ti, tj) = (ss.floor(), tt.floor());
        let (fs, ft) = (ss - ti, tt - tj);
        // Basket weave: planks run along s in "even" tiles and along t in "odd" ones.
        let odd = fmod(ti + tj, F::c(2.0)).ge(one);
        let along = F::select(odd, ft, fs);
        let across = F::select(odd, fs, ft) * F::c(nplanks);
        let pk = across.floor();
        let w = across - pk;

        // Grooves: along the plank sides (in plank widths) and at the plank ends (the same
        // width in tile units).
        let gw = self.groovewidth * 0.5;
        let side = filterstep(F::c(gw), w) - filterstep(F::c(1.0 - gw), w);
        let gl = gw / nplanks;
        let end = filterstep(F::c(gl), along) - filterstep(F::c(1.0 - gl), along);
        let in_plank = side * end;

        // Plank identity: its tile, orientation and index (cell centres, robust to rounding).
        let id = Vec3::new(ti + half, tj + half, pk + half);
        let rnd = vcellnoise(NoiseDomain::D3(id));
        // Plank-local coordinates in plank widths: x across, z along, y = depth (0 = surface).
        let x = w - half;
        let z = along * F::c(nplanks);
        let axis_x = (rnd.y - half) * F::c(4.0);
        let axis_depth = half + rnd.z * F::c(2.0);
        // Each plank reads the noise at its own place.
        let seed = rnd * F::c(97.0);
        let q = Vec3::new(x, zero, z * F::c(0.25)) + seed;
        let pert = snoise3(q * F::c(1.5)) + F::c(0.5) * snoise3(q * F::c(3.0));
        let dx = x - axis_x;
        let r = F::c(self.ringscale) * (dx * dx + axis_depth * axis_depth).sqrt() + F::c(self.ringnoise) * pert;
        let f = r - r.floor();
        let ring = smoothstep(zero, F::c(0.8), f) - smoothstep(F::c(0.83), one, f);
        let gs = F::c(self.grainscale);
        // Fine grain: stretched along the plank.
        let grain = F::c(0.85) + F::c(0.15) * snoise3(Vec3::new(gs * x, zero, gs * F::c(1.0 / 24.0) * z) + seed);
        let tint = one + F::c(self.plankvary) * (rnd.x - half);
        let light = Color::from_array(self.lightwood);
        let wood = (light + (Color::from_array(self.darkwood) - light) * ring) * (grain * tint);
        (in_plank, wood)
    }
}

impl SurfaceShader for Parquet {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::S | GlobalSet::T
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let (in_plank, wood) = self.pattern(g.s, g.t);
        let groove = Color::from_array(self.groovecolor);
        let ct = groove + (wood - groove) * in_plank;
        let finish = Finish {
            ka: self.Ka,
            kd: self.Kd,
            ks: self.Ks,
            roughness: self.roughness,
            specularcolor: self.specularcolor,
        };
        let l = finish.light_sums(ctx, e, nf, v);
        let c = finish.matte_part(ct, &l) + finish.specular_part(&l) * in_plank;
        SurfaceOutput { Ci: g.Os * c, Oi: g.Os }
    }
}
