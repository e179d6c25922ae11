/*
 * granite — turbulence (a fractal sum of |snoise|) between a dark and a light stone
 * colour (RenderMan Companion / BMRT granite). Port of shaders/src/surfaces/granite.rs:
 *   sum = Σ_o |snoise(2^o·PP)| / 2^o over `octaves` octaves, PP = frequency·P + offset
 *   Ct  = Cs·mix(darkcolor, lightcolor, clamp(contrast·sum, 0, 1)), plastic lighting.
 */
#include "anysl.h"

surface granite(
    uniform float Ka = 1;
    uniform float Kd = 0.8;
    uniform float Ks = 0.2;
    uniform float roughness = 0.1;
    uniform color specularcolor = 1;
    uniform float frequency = 4;                       /* base frequency of the turbulence */
    uniform vector offset = vector (1.5, 0.75, 2.25);  /* offset of the noise domain */
    uniform float octaves = 6;                         /* rounded, clamped to 1..16 */
    uniform float contrast = 1.5;                      /* gain from turbulence to the mix */
    uniform color darkcolor = color (0.20, 0.18, 0.17);
    uniform color lightcolor = color (0.95, 0.92, 0.88);)
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);

    point PP = P * frequency + offset;
    /* A uniform trip count: the same for every point. */
    uniform float noct = clamp(round(octaves), 1, 16);
    uniform float freq = 1;
    uniform float o;
    float sum = 0;
    for (o = 0; o < noct; o += 1) {
        sum += abs(snoise(PP * freq)) * (1 / freq);
        freq *= 2;
    }

    float tc = clamp(contrast * sum, 0, 1);
    color Ct = Cs * (darkcolor + (lightcolor - darkcolor) * tc);
    Oi = Os;
    Ci = Os * anysl_plastic(Nf, V, Ct, Ka, Kd, Ks, roughness, specularcolor);
}
