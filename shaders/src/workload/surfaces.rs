//! The four shaders of the shading workload (§5), written as ordinary anysl shaders: they read
//! the globals (`P`, `N`, `I`), call the standard library and light through the context.

use anysl_core::prelude::*;

/// §3: `Cs ⊙ (Ka·Ca + Kd·diff) + Ks·spec`, with `Ca = ambient()` and the two light sums of
/// one `illuminance` loop (`diff = Σ Cl·max(N·L, 0)`, `spec = Σ Cl·(N·L > 0 ? max(N·H, 0)^e : 0)`,
/// `e = 1/roughness`) — [`diffuse_specular`] computes exactly that. `illum(P, N, V, …)` takes
/// the unit normal and the unit vector to the eye of §2 as they are: `N` as given (every hit
/// faces the eye: no `faceforward`), `V = -I`, and its result is `Ci`.
#[inline(always)]
fn illum<F: ShadingFloat, C: ShadingContext<F>>(
    ctx: &mut C,
    e: &mut Exec<F>,
    cs: Color<F>,
    [ka, kd, ks, roughness]: [f64; 4],
) -> SurfaceOutput<F> {
    let g = *ctx.globals();
    let ca = ambient(ctx, e);
    let (diff, spec) = diffuse_specular(ctx, e, g.N, -g.I, F::c(roughness));
    let c = cs * (ca * F::c(ka) + diff * F::c(kd)) + spec * F::c(ks);
    SurfaceOutput { Ci: c, Oi: g.Os }
}

/// The workload's noise (§4.4): Perlin's improved noise with the table-free hash, unclamped.
#[inline(always)]
fn noise<F: ShadingFloat>(x: F, y: F, z: F) -> F {
    perlin3(Vec3::new(x, y, z), None, 0)
}

anysl_core::shader_params! {
    /// Workload §5(a), Phong/Blinn plastic: a constant surface colour under the §3 model.
    pub struct WorkloadPlastic: surface "workload_plastic" {
        /// Surface colour.
        uniform color surfacecolor = [0.80, 0.25, 0.15];
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.80;
        /// Specular coefficient.
        uniform float Ks = 0.50;
        /// Highlight roughness (Blinn exponent `1/roughness` = 12.5).
        uniform float roughness = 0.08;
    }
}

impl SurfaceShader for WorkloadPlastic {
    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let cs = Color::from_array(self.surfacecolor);
        illum(ctx, e, cs, [self.Ka, self.Kd, self.Ks, self.roughness])
    }
}

anysl_core::shader_params! {
    /// Workload §5(b), a solid 3D checker on object-space P:
    /// `q = floor(f·P.x) + floor(f·P.y) + floor(f·P.z)` as two's-complement integers,
    /// `oddcolor` where `q & 1 == 1`, else `evencolor`.
    pub struct WorkloadChecker: surface "workload_checker" {
        /// Checks per unit length along each axis.
        uniform float frequency = 4.0;
        /// Colour of the cells with odd `q`.
        uniform color oddcolor = [0.10, 0.20, 0.45];
        /// Colour of the cells with even `q`.
        uniform color evencolor = [0.90, 0.85, 0.70];
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.80;
        /// Specular coefficient.
        uniform float Ks = 0.30;
        /// Highlight roughness.
        uniform float roughness = 0.08;
    }
}

impl SurfaceShader for WorkloadChecker {
    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let p = ctx.globals().P * F::c(self.frequency);
        // The cell sum in integer lanes (wrapping, as int32 would), then its low bit.
        let q = p.x.floor_bits().wrapping_add(p.y.floor_bits()).wrapping_add(p.z.floor_bits());
        let one = F::Bits::splat(1);
        let odd = (q & one).eq_mask(one);
        let cs = Color::select(odd, Color::from_array(self.oddcolor), Color::from_array(self.evencolor));
        illum(ctx, e, cs, [self.Ka, self.Kd, self.Ks, self.roughness])
    }
}

anysl_core::shader_params! {
    /// Workload §5(c), wood: rings around the z axis perturbed by noise, and fine grain:
    /// `r = ringscale·√(x² + y²) + 1.5·noise(2P + (0.375, 1.25, 2.625))`, `f = r - floor(r)`,
    /// `ring = smoothstep(0, 0.8, f) - smoothstep(0.83, 1, f)`,
    /// `grain = 0.8 + 0.2·noise(48x, 48y, 1.5z)`, `Cs = (light + ring·(dark - light))·grain`.
    pub struct WorkloadWood: surface "workload_wood" {
        /// Rings per unit distance from the z axis.
        uniform float ringscale = 8.0;
        /// Colour between the rings.
        uniform color lightwood = [0.70, 0.45, 0.22];
        /// Colour of the rings.
        uniform color darkwood = [0.30, 0.15, 0.06];
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.75;
        /// Specular coefficient.
        uniform float Ks = 0.40;
        /// Highlight roughness.
        uniform float roughness = 0.08;
    }
}

impl SurfaceShader for WorkloadWood {
    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let p = ctx.globals().P;
        let two = F::c(2.0);
        let n1 = noise(two * p.x + F::c(0.375), two * p.y + F::c(1.25), two * p.z + F::c(2.625));
        let r = F::c(self.ringscale) * (p.x * p.x + p.y * p.y).sqrt() + F::c(1.5) * n1;
        let f = r - r.floor();
        let ring = smoothstep(F::c(0.0), F::c(0.8), f) - smoothstep(F::c(0.83), F::c(1.0), f);
        let n2 = noise(F::c(48.0) * p.x, F::c(48.0) * p.y, F::c(1.5) * p.z);
        let grain = F::c(0.8) + F::c(0.2) * n2;
        let light = Color::from_array(self.lightwood);
        let cs = (light + (Color::from_array(self.darkwood) - light) * ring) * grain;
        illum(ctx, e, cs, [self.Ka, self.Kd, self.Ks, self.roughness])
    }
}

anysl_core::shader_params! {
    /// Workload §5(d), granite: turbulence `turb = Σ_{o<6} |noise(2^o·Q)| / 2^o` of
    /// `Q = 4P + (1.5, 0.75, 2.25)`, `t = clamp(1.5·turb, 0, 1)`, `Cs = dark + t·(light - dark)`.
    pub struct WorkloadGranite: surface "workload_granite" {
        /// Scale of P in the noise domain.
        uniform float frequency = 4.0;
        /// Offset of the noise domain.
        uniform vector offset = [1.5, 0.75, 2.25];
        /// Gain from turbulence to the dark→light mix.
        uniform float contrast = 1.5;
        /// Colour where the turbulence is 0.
        uniform color darkcolor = [0.20, 0.18, 0.17];
        /// Colour where the scaled turbulence reaches 1.
        uniform color lightcolor = [0.95, 0.92, 0.88];
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.80;
        /// Specular coefficient.
        uniform float Ks = 0.20;
        /// Highlight roughness.
        uniform float roughness = 0.08;
    }
}

/// Octaves of the granite turbulence (a fixed trip count, unrolled).
const GRANITE_OCTAVES: u32 = 6;

impl SurfaceShader for WorkloadGranite {
    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let q = ctx.globals().P * F::c(self.frequency) + Vec3::from_array(self.offset);
        let mut turb = F::c(0.0);
        for o in 0..GRANITE_OCTAVES {
            let s = F::c(f64::from(1u32 << o));
            turb += noise(s * q.x, s * q.y, s * q.z).abs() * F::c(1.0 / f64::from(1u32 << o));
        }
        let t = clamp(F::c(self.contrast) * turb, F::c(0.0), F::c(1.0));
        let dark = Color::from_array(self.darkcolor);
        let cs = dark + (Color::from_array(self.lightcolor) - dark) * t;
        illum(ctx, e, cs, [self.Ka, self.Kd, self.Ks, self.roughness])
    }
}
