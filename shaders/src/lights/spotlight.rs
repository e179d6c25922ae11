//! `spotlight` — a point light restricted to a cone, with a soft edge.

use anysl_core::prelude::*;

anysl_core::shader_params! {
    /// RSL `spotlight` (RenderMan Interface 3.2 standard shader): with
    /// `A = normalize(to - from)` and `cosangle = L·A/|L|`,
    /// `illuminate(from, A, coneangle) { Cl = intensity·lightcolor·cosangle^beamdistribution
    /// / (L·L) · smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle) }`.
    /// Angles are in radians (the defaults are `radians(30)` and `radians(5)`).
    pub struct SpotLight: light "spotlight" {
        /// Brightness.
        uniform float intensity = 1.0;
        /// Colour.
        uniform color lightcolor = [1.0, 1.0, 1.0];
        /// Position.
        uniform point from = [0.0, 0.0, 0.0];
        /// A point the spot is aimed at.
        uniform point to = [0.0, 0.0, 1.0];
        /// Half-angle of the cone, in radians.
        uniform float coneangle = 0.523_598_775_598_298_8;
        /// Width of the soft edge inside the cone, in radians.
        uniform float conedeltaangle = 0.087_266_462_599_716_48;
        /// Exponent of the cosine fall-off towards the cone's edge.
        uniform float beamdistribution = 2.0;
    }
}

impl LightShader for SpotLight {
    #[inline(always)]
    fn emission(&self) -> Option<Emission> {
        Some(Emission::Local)
    }

    #[inline(always)]
    fn light<F: ShadingFloat>(&self, _e: &mut Exec<F>, ps: Vec3<F>) -> LightOutput<F> {
        let zero = F::c(0.0);
        let from = Vec3::from_array(self.from);
        let axis = (Vec3::from_array(self.to) - from).normalize();
        let cosoutside = F::c(self.coneangle.cos());
        let cosinside = F::c((self.coneangle - self.conedeltaangle).cos());
        let (l, lit) = illuminate(ps, from, Some((axis, F::c(self.coneangle))));
        let len2 = l.dot(l);
        let at_light = len2.le(zero);
        let safe_len2 = F::select(at_light, F::c(1.0), len2);
        let cosangle = F::select(at_light, F::c(1.0), l.dot(axis) / safe_len2.sqrt());
        let beam = cosangle.max(zero).pow(F::c(self.beamdistribution));
        let atten = beam / len2 * smoothstep(cosoutside, cosinside, cosangle);
        let cl = Color::from_array(self.lightcolor) * (F::c(self.intensity) * atten);
        LightOutput { cl, l, lit, emission: Emission::Local }
    }
}
