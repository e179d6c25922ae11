/*
 * plastic — the paper's "Phong": Lambertian diffuse plus a Blinn highlight
 * (RenderMan Interface 3.2 standard shader). Port of shaders/src/surfaces/plastic.rs:
 *   Oi = Os
 *   Ci = Os·(Cs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness))
 */
#include "anysl.h"

surface plastic(
    uniform float Ka = 1;           /* ambient coefficient */
    uniform float Kd = 0.5;         /* diffuse coefficient */
    uniform float Ks = 0.5;         /* specular coefficient */
    uniform float roughness = 0.1;  /* Blinn roughness (exponent 1/roughness) */
    uniform color specularcolor = 1;)
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * anysl_plastic(Nf, V, Cs, Ka, Kd, Ks, roughness, specularcolor);
}
