/*
 * checker — the classic RenderMan checkerboard on (s, t) with plastic lighting.
 * Port of shaders/src/surfaces/checker.rs. whitecolor where mod(s·frequency, 1) and
 * mod(t·frequency, 1) fall in the same half period, blackcolor elsewhere; both check
 * edges are box-filtered with filterstep (exactly step without derivatives).
 *   Ci = Os·(Ct·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness))
 *   Oi = Os
 */
#include "anysl.h"

surface checker(
    uniform float Kd = 0.5;
    uniform float Ka = 0.1;
    uniform float Ks = 0.3;
    uniform float roughness = 0.1;
    uniform float frequency = 10;   /* check periods per unit of s and t */
    uniform color blackcolor = color (0, 0, 0);
    uniform color whitecolor = color (1, 1, 1);
    uniform color specularcolor = 1;)
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);

    float a = anysl_filtered_square(s * frequency);
    float b = anysl_filtered_square(t * frequency);
    /* Filtered XOR: black where exactly one coordinate is in its upper half period. */
    float k = a + b - 2 * a * b;
    color Ct = whitecolor + (blackcolor - whitecolor) * k;

    Oi = Os;
    Ci = Os * anysl_plastic(Nf, V, Ct, Ka, Kd, Ks, roughness, specularcolor);
}
