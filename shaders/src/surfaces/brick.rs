//! `brick` — running-bond brick on (s, t), after the RenderMan Companion / Peachey's brick.

use crate::common::{view_frame, Finish, VIEW_GLOBALS};
use anysl_core::prelude::*;
use anysl_core::GlobalSet;

anysl_core::shader_params! {
    /// Running-bond brickwork on (s, t) (Peachey's `brick`, *Texturing & Modeling* ch. 2,
    /// after the RenderMan Companion): bricks of `brickwidth × brickheight` separated by
    /// mortar joints of `mortarthickness`, every other row shifted by `rowvary` brick lengths.
    /// The joints are box-filtered with `filterstep` (exactly `step` without derivatives) and
    /// each brick's colour varies by `±brickvary/2` with the `cellnoise` of its index.
    /// Matte lighting: `Ci = Os·Ct·(Ka·ambient() + Kd·diffuse(Nf))`, `Oi = Os`.
    pub struct Brick: surface "brick" uses_derivatives = true {
        /// Ambient coefficient.
        uniform float Ka = 1.0;
        /// Diffuse coefficient.
        uniform float Kd = 1.0;
        /// Brick length along s.
        uniform float brickwidth = 0.25;
        /// Brick height along t.
        uniform float brickheight = 0.08;
        /// Width of the mortar joints.
        uniform float mortarthickness = 0.01;
        /// Offset of alternate rows, in brick lengths.
        uniform float rowvary = 0.5;
        /// Relative colour variation between bricks.
        uniform float brickvary = 0.2;
        /// Brick colour.
        uniform color Cbrick = [0.5, 0.15, 0.14];
        /// Mortar colour.
        uniform color Cmortar = [0.5, 0.5, 0.5];
    }
}

impl Brick {
    /// The brick pattern at (s, t): `(in_brick, brick_colour)` with `in_brick` in [0, 1]
    /// (1 inside a brick, 0 in the mortar, filtered at the joints).
    #[inline(always)]
    #[must_use]
    pub fn pattern<F: ShadingFloat>(&self, s: F, t: F) -> (F, Color<F>) {
        let bmwidth = self.brickwidth + self.mortarthickness;
        let bmheight = self.brickheight + self.mortarthickness;
        let mwf = F::c(self.mortarthickness * 0.5 / bmwidth);
        let mhf = F::c(self.mortarthickness * 0.5 / bmheight);
        let one = F::c(1.0);
        let tt = t / F::c(bmheight);
        // Shift alternate rows (the Companion's `if (mod(tt*0.5, 1) > 0.5) ss += 0.5`).
        let odd_row = fmod(tt * F::c(0.5), one).gt(F::c(0.5));
        let ss = s / F::c(bmwidth) + F::select(odd_row, F::c(self.rowvary), F::c(0.0));
        let sbrick = ss.floor();
        let tbrick = tt.floor();
        let (fs, ft) = (ss - sbrick, tt - tbrick);
        let w = filterstep(mwf, fs) - filterstep(one - mwf, fs);
        let h = filterstep(mhf, ft) - filterstep(one - mhf, ft);
        // Cell centres, so the hash sees the brick index however `floor` rounds.
        let half = F::c(0.5);
        let n = cellnoise(NoiseDomain::D2(sbrick + half, tbrick + half));
        let vary = one + F::c(self.brickvary) * (n - half);
        (w * h, Color::from_array(self.Cbrick) * vary)
    }
}

impl SurfaceShader for Brick {
    #[inline(always)]
    fn globals_read(&self) -> GlobalSet {
        VIEW_GLOBALS | GlobalSet::S | GlobalSet::T
    }

    #[inline(always)]
    fn shade<F: ShadingFloat, C: ShadingContext<F>>(&self, ctx: &mut C, e: &mut Exec<F>) -> SurfaceOutput<F> {
        let g = *ctx.globals();
        let (nf, v) = view_frame(&g);
        let (inbrick, cbrick) = self.pattern(g.s, g.t);
        let mortar = Color::from_array(self.Cmortar);
        let ct = mortar + (cbrick - mortar) * inbrick;
        let finish = Finish { ka: self.Ka, kd: self.Kd, ks: 0.0, roughness: 1.0, specularcolor: [0.0; 3] };
        let l = finish.light_sums(ctx, e, nf, v);
        SurfaceOutput { Ci: g.Os * finish.matte_part(ct, &l), Oi: g.Os }
    }
}
