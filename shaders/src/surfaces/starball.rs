//! `starball` — a ball with a five-pointed star on each side and a band around its middle.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// The classic starball (the Luxo Jr. ball): in object-space spherical coordinates of
    /// `P` (star centres on the ±z axis, +y up), a five-pointed star of angular radius
    /// `starsize` with a tip pointing up, a band `|y| ≤ bandwidth` around the ball, the rest
    /// `ballcolor`; plastic lighting, `Oi = Os`.
    pub struct Starball: surface "starball" {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 0.5;
        /// Specular coefficient.
        uniform float Ks = 0.5;
        /// Highlight roughness.
        uniform float roughness = 0.1;
        /// Highlight colour.
        uniform color specularcolor = [1.0, 1.0, 1.0];
        /// Colour of the stars.
        uniform color starcolor = [0.90, 0.10, 0.05];
        /// Colour of the band.
        uniform color bandcolor = [0.05, 0.20, 0.80];
        /// Colour of the rest of the ball.
        uniform color ballcolor = [1.00, 0.80, 0.05];
        /// Angular radius of the star's tips, in radians.
        uniform float starsize = 0.45;
        /// Half-height of the band (in y on the unit ball).
        uniform float bandwidth = 0.2;
    }
}

/// Ratio of inner to outer radius of a regular pentagram: `sin 18° / sin 126°`.
const PENTAGRAM_RATIO: f64 = 0.381_966_011_250_105_2;

impl Starball {
    /// The surface colour at object-space `p`.
    #[inline(always)]
    #[must_use]
    pub fn color<F: ShadingFloat>(&self, p: Vec3<F>) -> Color<F> {
        let d = p.normalize();
        // Polar coordinates around the nearer star centre (+z or -z).
        let r = d.z.abs().min(F::c(1.0)).acos();
        let phi = d.y.atan2(d.x);
        // Fold the angle into one half-sector: 0 at a tip, π/5 at the notch between tips.
        let sector = 2.0 * PI / 5.0;
        let a = (fmod(phi - F::c(PI / 2.0 - sector / 2.0), F::c(sector)) - F::c(sector / 2.0)).abs();
        let (qx, qy) = (r * a.cos(), r * a.sin());
        // Inside the star ⇔ on the centre's side of the edge from the tip T to the notch V.
        let rmax = self.starsize;
        let rmin = rmax * PENTAGRAM_RATIO;
        let (vx, vy) = (rmin * (PI / 5.0).cos(), rmin * (PI / 5.0).sin());
        let (ex, ey) = (F::c(vx - rmax), F::c(vy));
        let inside = (ex * qy - ey * (qx - F::c(rmax))).ge(F::c(0.0));
        let in_band = d.y.abs().le(F::c(self.bandwidth));
        let body = Color::select(in_band, Color::from_array(self.bandcolor), Color::from_array(self.ballcolor));
        Color::select(inside, Color::from_array(self.starcolor), body)
    }
}

impl SurfaceShader for Starball {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let ct = self.color(g.P);
        let finish = Finish {
            ka: self.Ka,
            kd: self.Kd,
            ks: self.Ks,
            roughness: self.roughness,
            specularcolor: self.specularcolor,
        };
        let c = finish.plastic(ctx, e, nf, v, ct);
        SurfaceOutput { Ci: g.Os * c, Oi: g.Os }
    }
}
