//! `pointlight` — light from a point, with inverse-square (or no) falloff.

use anysl_core::prelude::*;

anysl_core::shader_params! {
    /// RSL `pointlight`: `illuminate(from) { Cl = intensity·lightcolor / (L·L) }`.
    /// `falloff` generalises the distance law to `1/|L|^falloff`: 2 (the default) is the
    /// classic inverse square, 0 a light without falloff (as the shading workload's lights,
    /// see [`crate::table1_lights`]).
    pub struct PointLight: light "pointlight" {
        /// Brightness.
        uniform float intensity = 1.0;
        /// Colour.
        uniform color lightcolor = [1.0, 1.0, 1.0];
        /// Position.
        uniform point from = [0.0, 0.0, 0.0];
        /// Exponent of the distance falloff (2 = inverse square, 0 = none).
        uniform float falloff = 2.0;
    }
}

impl LightShader for PointLight {
    #[inline(always)]
    fn emission(&self) -> Option<Emission> {
        Some(Emission::Local)
    }

    #[inline(always)]
    fn light<F: ShadingFloat>(&self, _e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        let (l, lit) = illuminate(ps, Vec3::from_array(self.from), None);
        let c = Color::from_array(self.lightcolor) * F::c(self.intensity);
        // `falloff` is uniform: a branch on a parameter, not on a lane.
        let cl = if self.falloff == 0.0 {
            c
        } else if self.falloff == 2.0 {
            c / l.dot(l)
        } else {
            c / l.dot(l).pow(F::c(self.falloff * 0.5))
        };
        LightOutput { cl, l, lit, emission: Emission::Local }
    }

    /// Lights without falloff or with the inverse-square law; other falloffs have none.
    fn data(&self) -> Option<LightData> {
        let falloff = if self.falloff == 0.0 {
            Falloff::None
        } else if self.falloff == 2.0 {
            Falloff::InverseSquare
        } else {
            return None;
        };
        Some(LightData {
            kind: LightKind::Point,
            falloff,
            pos: self.from.map(|x| x as f32),
            cl: crate::lights::colour_times(self.lightcolor, self.intensity),
        })
    }
}
