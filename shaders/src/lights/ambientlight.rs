//! `ambientlight` — constant light without direction, seen by `ambient()`.

use anysl_core::prelude::*;

anysl_core::shader_params! {
    /// RSL `ambientlight`: `Cl = intensity·lightcolor`, `L = 0`; contributes to `ambient()`
    /// only.
    pub struct AmbientLight: light "ambientlight" {
        /// Brightness.
        uniform float intensity = 1.0;
        /// Colour.
        uniform color lightcolor = [1.0, 1.0, 1.0];
    }
}

impl LightShader for AmbientLight {
    #[inline(always)]
    fn emission(&self) -> Option<Emission> {
        Some(Emission::Ambient)
    }

    #[inline(always)]
    fn light<F: ShadingFloat>(&self, _e: &mut Exec<F>, _ps: Vec3<F>) -> LightOutput<F> {
        let cl = Color::from_array(self.lightcolor) * F::c(self.intensity);
        LightOutput { cl, l: Vec3::zero(), lit: F::Mask::splat(true), emission: Emission::Ambient }
    }

    fn data(&self) -> Option<LightData> {
        let cl = crate::lights::colour_times(self.lightcolor, self.intensity);
        Some(LightData { kind: LightKind::Ambient, falloff: Falloff::None, pos: [0.0; 3], cl })
    }
}
