//! The workload's scene setup (§1–2): a 512×512 pinhole camera looking at the unit sphere,
//! intersected in f64, and the hit points as shading inputs in structure-of-arrays form.

use anysl_core::prelude::*;
use anysl_core::{LightSource, PointContext, SurfaceVisitor};

use super::WorkloadShader;

/// Image side in pixels.
pub const SIZE: usize = 512;
/// Camera position.
const EYE: [f64; 3] = [0.0, 0.0, 3.0];
/// Half-extent of the image plane at distance 1.
const HALF_EXTENT: f64 = 0.375;
/// Inputs are padded to a multiple of this many points, so every SIMD width divides them.
pub const PAD: usize = 32;

/// Input arrays of [`WorkloadScene`] (each `x, y, z`).
const P: usize = 0;
const N: usize = 3;
const V: usize = 6;
/// Screen-space derivative seeds (f32 only): ∂P/∂x, ∂P/∂y, ∂N/∂x, ∂N/∂y.
const DPDX: usize = 9;
const DPDY: usize = 12;
const DNDX: usize = 15;
const DNDY: usize = 18;
const F32_FIELDS: usize = 21;
const F64_FIELDS: usize = 9;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    v.map(|c| c / l)
}

/// The primary ray direction through the centre of pixel `(row, col)` (§1; fractional and
/// out-of-image pixels give the neighbouring rays of the footprint).
fn ray_dir(row: f64, col: f64) -> [f64; 3] {
    let step = 2.0 / SIZE as f64;
    let sx = ((col + 0.5) * step - 1.0) * HALF_EXTENT;
    let sy = (1.0 - (row + 0.5) * step) * HALF_EXTENT;
    normalize([sx, sy, -1.0])
}

/// §2: the hit point of the ray `(EYE, d)` on the unit sphere, in the numerically stable form.
fn intersect(d: [f64; 3]) -> Option<[f64; 3]> {
    let b = dot(EYE, d);
    let q = [EYE[0] - b * d[0], EYE[1] - b * d[1], EYE[2] - b * d[2]];
    let h = 1.0 - dot(q, q);
    if h > 0.0 {
        let t = -b - h.sqrt();
        Some([EYE[0] + t * d[0], EYE[1] + t * d[1], EYE[2] + t * d[2]])
    } else {
        None
    }
}

/// The shading inputs of the workload: P, N, V of every hit pixel in row-major pixel order,
/// computed in f64 (§2) and kept both in f64 (for f64 instantiations) and rounded to f32 (for
/// everything else), padded to a multiple of [`PAD`] points by repeating the last hit.
///
/// Each hit also carries a pixel footprint for dual-number instantiations: ∂P/∂x and ∂P/∂y
/// per pixel step (the neighbouring rays meeting the tangent plane at P) and the matching
/// ∂N (the unit sphere's normal is P). Other instantiations ignore them.
#[derive(Clone, Debug)]
pub struct WorkloadScene {
    n_hit: usize,
    /// Points per field including the padding.
    padded: usize,
    pixels: Vec<u32>,
    f32s: Vec<Vec<f32>>,
    f64s: Vec<Vec<f64>>,
    /// `I = -V` in f32, component by component (padded like the fields).
    eye_in: [Vec<f32>; 3],
}

impl Default for WorkloadScene {
    fn default() -> Self {
        Self::new()
    }
}

impl WorkloadScene {
    /// Camera, rays and intersections (not part of a timed call).
    #[must_use]
    pub fn new() -> Self {
        let mut pixels = Vec::new();
        let mut f64s = vec![Vec::new(); F64_FIELDS];
        let mut f32s = vec![Vec::new(); F32_FIELDS];
        for row in 0..SIZE {
            for col in 0..SIZE {
                let d = ray_dir(row as f64, col as f64);
                let Some(p) = intersect(d) else { continue };
                let n = normalize(p);
                let v = d.map(|c| -c);
                // Footprint: the rays one pixel right / down, met in the tangent plane at P.
                let transfer = |d2: [f64; 3]| {
                    let t = dot([p[0] - EYE[0], p[1] - EYE[1], p[2] - EYE[2]], n) / dot(d2, n);
                    [0, 1, 2].map(|k| EYE[k] + t * d2[k] - p[k])
                };
                let dpdx = transfer(ray_dir(row as f64, col as f64 + 1.0));
                let dpdy = transfer(ray_dir(row as f64 + 1.0, col as f64));
                // N = P on the unit sphere: dN = dP minus its normal part.
                let dn = |dp: [f64; 3]| {
                    let k = dot(dp, n);
                    [0, 1, 2].map(|i| dp[i] - n[i] * k)
                };
                let fields = [p, n, v, dpdx, dpdy, dn(dpdx), dn(dpdy)];
                for (f, vals) in fields.iter().enumerate() {
                    for k in 0..3 {
                        if f * 3 < F64_FIELDS {
                            f64s[f * 3 + k].push(vals[k]);
                        }
                        f32s[f * 3 + k].push(vals[k] as f32);
                    }
                }
                pixels.push((row * SIZE + col) as u32);
            }
        }
        let n_hit = pixels.len();
        let padded = n_hit.div_ceil(PAD) * PAD;
        for a in &mut f64s {
            let last = *a.last().expect("the sphere is in view");
            a.resize(padded, last);
        }
        for a in &mut f32s {
            let last = *a.last().expect("the sphere is in view");
            a.resize(padded, last);
        }
        let eye_in = core::array::from_fn(|c| f32s[V + c].iter().map(|v| -v).collect());
        Self { n_hit, padded, pixels, f32s, f64s, eye_in }
    }

    /// Number of hit points (183 020).
    #[must_use]
    pub fn n_hit(&self) -> usize {
        self.n_hit
    }

    /// Number of points including the padding (a multiple of [`PAD`]).
    #[must_use]
    pub fn padded_len(&self) -> usize {
        self.f32s[0].len()
    }

    /// Pixel index `row·512 + col` of each hit point.
    #[must_use]
    pub fn pixels(&self) -> &[u32] {
        &self.pixels
    }

    /// The hit mask of the image, row-major (`ref/mask.npy`).
    #[must_use]
    pub fn mask(&self) -> Vec<bool> {
        let mut m = vec![false; SIZE * SIZE];
        for &p in &self.pixels {
            m[p as usize] = true;
        }
        m
    }

    /// The f32 input arrays `[P.x, P.y, P.z, N.x, N.y, N.z, V.x, V.y, V.z]` (padded).
    #[must_use]
    pub fn inputs_f32(&self) -> [&[f32]; 9] {
        core::array::from_fn(|k| self.f32s[k].as_slice())
    }

    /// The f64 input arrays, as [`WorkloadScene::inputs_f32`].
    #[must_use]
    pub fn inputs_f64(&self) -> [&[f64]; 9] {
        core::array::from_fn(|k| self.f64s[k].as_slice())
    }

    /// The globals that differ from point to point as f32 arrays, points `start .. start +
    /// len`: `P`, `N` (which is also `Ng`) and `I = -V`, each as its x, y, z arrays — the
    /// structure-of-arrays form a loop over the point set reads (the JIT's points entry);
    /// the other globals are [`WorkloadScene::globals`]'s.
    ///
    /// # Panics
    /// When the range passes the padded inputs.
    #[must_use]
    pub fn varying_f32(&self, start: usize, len: usize) -> [[&[f32]; 3]; 3] {
        let r = start..start + len;
        let f = |k: usize| [0, 1, 2].map(|c| &self.f32s[k + c][r.clone()]);
        [f(P), f(N), [0, 1, 2].map(|c| &self.eye_in[c][r.clone()])]
    }

    /// Points `i .. i + F::LANES` of f32 field `k`: one range check for the packet instead of
    /// one per field (every field has [`WorkloadScene::padded_len`] points).
    ///
    /// # Panics
    /// When the points pass the padded inputs.
    #[inline(always)]
    fn f32_lanes<F: ShadingFloat>(&self, k: usize, i: usize) -> &[f32] {
        assert!(k < F32_FIELDS && i + F::LANES <= self.padded, "points {i}.. of {} in field {k}", self.padded);
        // SAFETY: every field holds `self.padded` values (`new`), checked above.
        unsafe { core::slice::from_raw_parts(self.f32s.get_unchecked(k).as_ptr().add(i), F::LANES) }
    }

    /// The globals of points `i .. i + F::LANES`: `P`, `N` (= `Ng`), `I = -V`, the eye as `E`,
    /// `Cs = Os = 1`; P and N carry their pixel footprint as derivatives (used only by dual
    /// numbers).
    #[inline(always)]
    #[must_use]
    pub fn globals<F: ShadingFloat>(&self, i: usize) -> Globals<F> {
        let mut g = Globals {
            E: Vec3::from_array(EYE),
            Cs: Color::c(1.0, 1.0, 1.0),
            Os: Color::c(1.0, 1.0, 1.0),
            ..Globals::at(Vec3::zero())
        };
        self.set_points_whole(&mut g, i);
        g
    }

    /// Lanes `i .. i + F::LANES` of input field `k`: from the `f64` inputs for an accurate
    /// type, else one load of the `f32` ones.
    #[inline(always)]
    fn lanes<F: ShadingFloat>(&self, k: usize, i: usize) -> F {
        if F::UNIT_ROUNDOFF < 1e-10 && k < F64_FIELDS {
            F::from_lanes(&self.f64s[k][i..i + F::LANES])
        } else {
            F::load(self.f32_lanes::<F>(k, i))
        }
    }

    /// Field `k` with the derivatives in fields `dx`, `dy` for a type that carries them.
    #[inline(always)]
    fn seeded<F: ShadingFloat>(&self, k: usize, (dx, dy): (usize, usize), i: usize) -> F {
        let v = self.lanes::<F>(k, i);
        if F::HAS_DERIVS {
            v.with_derivs(self.lanes(dx, i), self.lanes(dy, i))
        } else {
            v
        }
    }

    /// [`WorkloadScene::set_points`] for a shader inlined into the loop that reads the
    /// globals (`WorkloadScene::globals`, the per-packet path of `shade`).
    #[inline(always)]
    fn set_points_whole<F: ShadingFloat>(&self, g: &mut Globals<F>, i: usize) {
        // Each value built in registers and assigned whole: the shader that reads them is
        // inlined into the loop (`WorkloadScene::shade`), and its whole-value loads are
        // forwarded from these stores (written packet by packet, `set_points`, they measured
        // 13–16 % slower with `Pair`s: a wide load of narrower stores is not forwarded).
        let p = |c: usize| self.seeded(P + c, (DPDX + c, DPDY + c), i);
        let n = |c: usize| self.seeded(N + c, (DNDX + c, DNDY + c), i);
        (g.P.x, g.P.y, g.P.z) = (p(0), p(1), p(2));
        (g.N.x, g.N.y, g.N.z) = (n(0), n(1), n(2));
        (g.Ng.x, g.Ng.y, g.Ng.z) = (g.N.x, g.N.y, g.N.z);
        (g.I.x, g.I.y, g.I.z) = (-self.lanes::<F>(V, i), -self.lanes::<F>(V + 1, i), -self.lanes::<F>(V + 2, i));
    }

    /// Writes the globals that differ from packet to packet — `P`, `N` (= `Ng`) and `I` of
    /// points `i .. i + F::LANES`, with their footprints for dual numbers — into `g`; the
    /// others are the same for every packet ([`WorkloadScene::globals`]). A shading loop keeps
    /// one context and rewrites only these: a shader behind a call boundary (JIT code reads
    /// the globals in memory) then costs no rebuilt `Globals` per packet. Written packet by
    /// packet for such a shader; the loop that inlines the shader (`shade`) assigns whole
    /// values instead (`set_points_whole`), which its own loads are forwarded from.
    #[inline(always)]
    pub fn set_points<F: ShadingFloat>(&self, g: &mut Globals<F>, i: usize) {
        // Component by component, each lane vector written straight into its global
        // (`ShadingFloat::load_into`): a value built first and assigned whole goes through a
        // temporary copied with moves wider than the stores that made it (a 64-byte load
        // from two 32-byte stores at 8 lanes), which stalls store forwarding on every packet
        // of a shader that reads the globals in memory (JIT code). `Ng` is loaded again
        // rather than copied from `N` for the same reason.
        let set3 = |dst: [&mut F; 3], k: usize, derivs: Option<(usize, usize)>, neg: bool| {
            for (c, d) in dst.into_iter().enumerate() {
                if F::HAS_DERIVS || (F::UNIT_ROUNDOFF < 1e-10 && k < F64_FIELDS) {
                    let v: F = match derivs {
                        Some((dx, dy)) => self.seeded(k + c, (dx + c, dy + c), i),
                        None => self.lanes(k + c, i),
                    };
                    *d = if neg { -v } else { v };
                } else {
                    d.load_into(self.f32_lanes::<F>(k + c, i), neg);
                }
            }
        };
        set3([&mut g.P.x, &mut g.P.y, &mut g.P.z], P, Some((DPDX, DPDY)), false);
        set3([&mut g.N.x, &mut g.N.y, &mut g.N.z], N, Some((DNDX, DNDY)), false);
        set3([&mut g.Ng.x, &mut g.Ng.y, &mut g.Ng.z], N, Some((DNDX, DNDY)), false);
        // `V` holds the direction to the eye; `I` is its negation (derivatives zero).
        set3([&mut g.I.x, &mut g.I.y, &mut g.I.z], V, None, true);
    }

    /// One shading call over points `start .. start + out[0].len()` (a multiple of `F::LANES`)
    /// with instantiation `F`: writes `Ci` (r, g, b) to `out` as f32 lane values (the value
    /// part for duals, the midpoint for intervals). Monomorphized per concrete shader through
    /// [`SurfaceShader::visit`], so the shader is inlined into the loop.
    pub fn shade<F: ShadingFloat, L: LightSource>(
        &self,
        shader: &WorkloadShader,
        lights: &[L],
        start: usize,
        out: [&mut [f32]; 3],
    ) {
        struct Job<'a, F, L> {
            scene: &'a WorkloadScene,
            lights: &'a [L],
            start: usize,
            out: [&'a mut [f32]; 3],
            _f: core::marker::PhantomData<F>,
        }
        impl<F: ShadingFloat, L: LightSource> SurfaceVisitor for Job<'_, F, L> {
            type Output = ();
            #[inline(never)]
            fn visit<S: SurfaceShader>(self, shader: &S) {
                self.scene.shade_surface::<F, S, L>(shader, self.lights, self.start, self.out);
            }
        }
        shader.visit(Job::<F, L> { scene: self, lights, start, out, _f: core::marker::PhantomData });
    }

    /// [`WorkloadScene::shade`] for any surface shader (an interpreted or JIT-compiled `.sl`
    /// shader, …): the same globals and lights, one `SurfaceShader::shade` per `F::LANES`
    /// points.
    ///
    /// # Panics
    /// When the three outputs differ in length, the length is not a multiple of `F::LANES` or
    /// the range passes the padded inputs.
    #[inline(always)]
    pub fn shade_surface<F: ShadingFloat, S: SurfaceShader, L: LightSource>(
        &self,
        shader: &S,
        lights: &[L],
        start: usize,
        out: [&mut [f32]; 3],
    ) {
        let [r, g, b] = out;
        let len = self.check_range::<F>(start, [r.len(), g.len(), b.len()]);
        if len == 0 {
            return;
        }
        let mut ctx = PointContext::new(self.globals::<F>(start), lights);
        let mut k = 0;
        while k < len {
            self.set_points(&mut ctx.globals, start + k);
            let mut e = Exec::<F>::new();
            let ci = shader.shade(&mut ctx, &mut e).Ci;
            ci.r.store(&mut r[k..]);
            ci.g.store(&mut g[k..]);
            ci.b.store(&mut b[k..]);
            k += F::LANES;
        }
    }

    /// [`WorkloadScene::shade`] for a shader that shades many chunks of `F::LANES` points per
    /// call (the batched interpreter): `shade_batch(ctxs, outs)` receives up to `chunks`
    /// contexts of consecutive points and writes each chunk's output to `outs` (as long as
    /// `ctxs`). The contexts and the output buffer are allocated once per call, not per batch.
    ///
    /// # Panics
    /// As [`WorkloadScene::shade_surface`], and when `chunks` is 0.
    pub fn shade_batched<F: ShadingFloat, L: LightSource>(
        &self,
        lights: &[L],
        start: usize,
        out: [&mut [f32]; 3],
        chunks: usize,
        mut shade_batch: impl FnMut(&mut [PointContext<'_, F, L>], &mut [SurfaceOutput<F>]),
    ) {
        assert!(chunks > 0, "a batch needs at least one chunk");
        let [r, g, b] = out;
        let len = self.check_range::<F>(start, [r.len(), g.len(), b.len()]);
        let mut ctxs = Vec::with_capacity(chunks);
        let mut outs = vec![SurfaceOutput { Ci: Color::<F>::zero(), Oi: Color::zero() }; chunks];
        let mut k = 0;
        while k < len {
            let n = chunks.min((len - k) / F::LANES);
            ctxs.clear();
            ctxs.extend((0..n).map(|c| PointContext::new(self.globals::<F>(start + k + c * F::LANES), lights)));
            shade_batch(&mut ctxs, &mut outs[..n]);
            for (c, o) in outs[..n].iter().enumerate() {
                let (at, col) = (k + c * F::LANES, o.Ci);
                col.r.store(&mut r[at..]);
                col.g.store(&mut g[at..]);
                col.b.store(&mut b[at..]);
            }
            k += n * F::LANES;
        }
    }

    /// Checks an output range of the shading calls; returns its length.
    #[inline(always)]
    fn check_range<F: ShadingFloat>(&self, start: usize, lens: [usize; 3]) -> usize {
        let len = lens[0];
        assert!(
            len.is_multiple_of(F::LANES) && lens[1] == len && lens[2] == len,
            "outputs of {lens:?} points for {} lanes",
            F::LANES
        );
        assert!(start + len <= self.padded_len(), "points {start}..{} of {}", start + len, self.padded_len());
        len
    }

    /// Shades every point with `F` on the calling thread; returns `Ci` as three padded arrays.
    #[must_use]
    pub fn shade_all<F: ShadingFloat, L: LightSource>(&self, shader: &WorkloadShader, lights: &[L]) -> [Vec<f32>; 3] {
        let n = self.padded_len();
        let [mut r, mut g, mut b] = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        self.shade::<F, L>(shader, lights, 0, [&mut r, &mut g, &mut b]);
        [r, g, b]
    }

    /// Shades the points with `F` and keeps full lane values as f64 (for the f64 reference).
    #[must_use]
    pub fn shade_all_f64<F: ShadingFloat, L: LightSource>(
        &self,
        shader: &WorkloadShader,
        lights: &[L],
    ) -> [Vec<f64>; 3] {
        struct Job<'a, F, L> {
            scene: &'a WorkloadScene,
            lights: &'a [L],
            _f: core::marker::PhantomData<F>,
        }
        impl<F: ShadingFloat, L: LightSource> SurfaceVisitor for Job<'_, F, L> {
            type Output = [Vec<f64>; 3];
            fn visit<S: SurfaceShader>(self, shader: &S) -> [Vec<f64>; 3] {
                let n = self.scene.padded_len();
                let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
                for k in (0..n).step_by(F::LANES) {
                    let mut ctx = PointContext::new(self.scene.globals::<F>(k), self.lights);
                    let ci = shader.shade(&mut ctx, &mut Exec::<F>::new()).Ci;
                    for (ch, v) in [ci.r, ci.g, ci.b].iter().enumerate() {
                        for l in 0..F::LANES {
                            out[ch][k + l] = v.lane(l);
                        }
                    }
                }
                out
            }
        }
        shader.visit(Job::<F, L> { scene: self, lights, _f: core::marker::PhantomData })
    }

    /// Scatters per-hit colours into a 512×512×3 image (`[row][col][channel]`, black
    /// background), as the reference arrays are laid out.
    #[must_use]
    pub fn to_image<T: Copy + Default>(&self, ci: &[Vec<T>; 3]) -> Vec<T> {
        let mut img = vec![T::default(); SIZE * SIZE * 3];
        for (k, &p) in self.pixels.iter().enumerate() {
            for ch in 0..3 {
                img[p as usize * 3 + ch] = ci[ch][k];
            }
        }
        img
    }
}
