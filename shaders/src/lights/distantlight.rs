//! `distantlight` — parallel light along a direction.

use anysl_core::prelude::*;

anysl_core::shader_params! {
    /// RSL `distantlight`: `solar(to - from, 0) { Cl = intensity·lightcolor }`.
    pub struct DistantLight: light "distantlight" {
        /// Brightness.
        uniform float intensity = 1.0;
        /// Colour.
        uniform color lightcolor = [1.0, 1.0, 1.0];
        /// Start of the direction the light travels.
        uniform point from = [0.0, 0.0, 0.0];
        /// End of the direction the light travels.
        uniform point to = [0.0, 0.0, 1.0];
    }
}

impl LightShader for DistantLight {
    #[inline(always)]
    fn emission(&self) -> Option<Emission> {
        Some(Emission::Distant)
    }

    #[inline(always)]
    fn light<F: ShadingFloat>(&self, _e: &mut Exec<F>, _ps: Vec3<F>) -> LightOutput<F> {
        let (l, lit) = solar(Vec3::from_array(self.to) - Vec3::from_array(self.from));
        let cl = Color::from_array(self.lightcolor) * F::c(self.intensity);
        LightOutput { cl, l, lit, emission: Emission::Distant }
    }

    fn data(&self) -> Option<LightData> {
        let cl = crate::lights::colour_times(self.lightcolor, self.intensity);
        // `to - from` in f32, as `light` forms it.
        let pos = core::array::from_fn(|i| self.to[i] as f32 - self.from[i] as f32);
        Some(LightData { kind: LightKind::Distant, falloff: Falloff::None, pos, cl })
    }
}
