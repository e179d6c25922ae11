/*
 * venus — Musgrave's Venus (Texturing & Modeling, 2nd ed., ch. 15), with +y as the
 * planet's axis. Port of shaders/src/surfaces/venus.rs. P is rotated about the axis by
 * angle = twist·2π·rsq + distortion·snoise(2P), rsq = x² + z² of normalize(P) (a
 * Coriolis shear strongest at the equator); then a = Σ omega^o·snoise(2^o·PP) over
 * `octaves` octaves, value = |offset + scale·a|, and the colour is a Catmull-Rom
 * spline of value/2 through a haze-to-cloud palette (first and last knots repeated).
 * Matte lighting (anysl_matte): Ci = Os·Ct·(Ka·ambient() + Kd·diffuse(Nf)), Oi = Os.
 */
#include "anysl.h"

surface venus(
    uniform float Ka = 1;
    uniform float Kd = 1;
    uniform float offset = 1;        /* added to the fBm before abs */
    uniform float scale = 0.6;       /* scale of the fBm */
    uniform float twist = 0.22;      /* Coriolis twist, turns at the equator */
    uniform float distortion = 0.3;  /* noise added to the twist angle, radians */
    uniform float omega = 0.65;      /* amplitude ratio between octaves */
    uniform float octaves = 8;)      /* rounded, clamped to 1..16 */
{
    normal Nf = faceforward(normalize(N), I, N);

    vector PN = normalize(P);
    float rsq = xcomp(PN) * xcomp(PN) + zcomp(PN) * zcomp(PN);
    float angle = twist * 2 * PI * rsq + distortion * snoise(P * 2);
    float sn = sin(angle);
    float cs = cos(angle);
    point PP = point (xcomp(P) * cs + zcomp(P) * sn, ycomp(P), zcomp(P) * cs - xcomp(P) * sn);

    /* A uniform trip count: the same for every point. */
    uniform float noct = clamp(round(octaves), 1, 16);
    uniform float l = 1;
    uniform float o = 1;
    uniform float i;
    float a = 0;
    for (i = 0; i < noct; i += 1) {
        a += o * snoise(PP * l);
        l *= 2;
        o *= omega;
    }
    float value = abs(offset + scale * a);

    color Ct = spline(value * 0.5,
                      color (0.30, 0.16, 0.06),
                      color (0.30, 0.16, 0.06),
                      color (0.55, 0.34, 0.13),
                      color (0.80, 0.62, 0.33),
                      color (0.93, 0.83, 0.58),
                      color (1.00, 0.96, 0.84),
                      color (1.00, 0.96, 0.84));

    Oi = Os;
    Ci = Os * anysl_matte(Nf, Ct, Ka, Kd);
}
