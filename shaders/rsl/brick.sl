/*
 * brick — running-bond brickwork on (s, t), after the RenderMan Companion /
 * Peachey's brick (Texturing & Modeling ch. 2). Port of shaders/src/surfaces/brick.rs.
 * Bricks of brickwidth × brickheight separated by mortar joints of mortarthickness,
 * every other row shifted by rowvary brick lengths; the joints are box-filtered with
 * filterstep and each brick's colour varies by ±brickvary/2 with the cellnoise of its
 * index. Matte lighting (anysl_matte): Ci = Os·Ct·(Ka·ambient() + Kd·diffuse(Nf)), Oi = Os.
 */
#include "anysl.h"

surface brick(
    uniform float Ka = 1;
    uniform float Kd = 1;
    uniform float brickwidth = 0.25;       /* brick length along s */
    uniform float brickheight = 0.08;      /* brick height along t */
    uniform float mortarthickness = 0.01;  /* width of the mortar joints */
    uniform float rowvary = 0.5;           /* offset of alternate rows, in brick lengths */
    uniform float brickvary = 0.2;         /* relative colour variation between bricks */
    uniform color Cbrick = color (0.5, 0.15, 0.14);
    uniform color Cmortar = color (0.5, 0.5, 0.5);)
{
    normal Nf = faceforward(normalize(N), I, N);

    uniform float bmwidth = brickwidth + mortarthickness;
    uniform float bmheight = brickheight + mortarthickness;
    uniform float mwf = mortarthickness * 0.5 / bmwidth;
    uniform float mhf = mortarthickness * 0.5 / bmheight;

    float tt = t / bmheight;
    /* Shift alternate rows (the Companion's `if (mod(tt*0.5, 1) > 0.5) ss += 0.5`). */
    float ss = s / bmwidth + ((mod(tt * 0.5, 1) > 0.5) ? rowvary : 0);
    float sbrick = floor(ss);
    float tbrick = floor(tt);
    float fs = ss - sbrick;
    float ft = tt - tbrick;
    float w = filterstep(mwf, fs) - filterstep(1 - mwf, fs);
    float h = filterstep(mhf, ft) - filterstep(1 - mhf, ft);
    float inbrick = w * h;

    /* Cell centres, so the hash sees the brick index however floor rounds. */
    float n = float cellnoise(sbrick + 0.5, tbrick + 0.5);
    float vary = 1 + brickvary * (n - 0.5);
    color cbrick = Cbrick * vary;

    color Ct = Cmortar + (cbrick - Cmortar) * inbrick;
    Oi = Os;
    Ci = Os * anysl_matte(Nf, Ct, Ka, Kd);
}
