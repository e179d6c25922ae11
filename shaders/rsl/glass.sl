/*
 * glass — a dielectric: Fresnel-weighted reflection and refraction rays plus a
 * highlight (after BMRT's glass). Port of shaders/src/surfaces/glass.rs. With
 * fresnel(I, Nf, eta') giving kr, kt, R, T:
 *   Ci = Cs·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness)
 *        + Kr·kr·trace(P, R) + Kt·kt·trace(P, T)
 *   Oi = 1
 * eta' is 1/eta where the ray enters (I·N < 0) and eta where it leaves. Each ray is
 * traced only where its weight is nonzero (no refraction ray under total internal
 * reflection). Note: Ci is not multiplied by Os.
 */
#include "anysl.h"

surface glass(
    uniform float Ka = 0;           /* clear glass has no matte part */
    uniform float Kd = 0;
    uniform float Ks = 0.5;
    uniform float Kr = 1;           /* weight of the reflection ray */
    uniform float Kt = 1;           /* weight of the refraction ray */
    uniform float roughness = 0.05;
    uniform float eta = 1.5;        /* index of refraction inside / outside */
    uniform color specularcolor = 1;)
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);

    /* The matte and highlight parts; uniform branches on the coefficients. */
    if (Ka != 0 || Kd != 0)
        Ci = anysl_plastic(Nf, V, Cs, Ka, Kd, Ks, roughness, specularcolor);
    else if (Ks != 0)
        Ci = specularcolor * Ks * specular(Nf, V, roughness);
    else
        Ci = 0;

    float ratio = ((I . N) < 0) ? 1 / eta : eta;
    float kr, kt;
    vector R, T;
    fresnel(I, Nf, ratio, kr, kt, R, T);
    float wr = kr * Kr;
    float wt = kt * Kt;
    if (wr > 0)
        Ci += trace(P, R) * wr;
    if (wt > 0)
        Ci += trace(P, T) * wt;
    Oi = 1;
}
