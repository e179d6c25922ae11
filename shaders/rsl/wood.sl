/*
 * wood — classic solid wood (after the RenderMan Companion / BMRT wood): growth rings
 * around the z axis, perturbed by noise, with fine grain. Port of
 * shaders/src/surfaces/wood.rs (shading workload §5(c)):
 *   r     = ringscale·sqrt(x² + y²) + 1.5·snoise(2P + (0.375, 1.25, 2.625))
 *   ring  = smoothstep(0, 0.8, f) - smoothstep(0.83, 1, f), f = r - floor(r)
 *   grain = 0.8 + 0.2·snoise(grainscale·x, grainscale·y, grainscale/32·z)
 *   Ct    = mix(lightwood, darkwood, ring)·grain, plastic lighting, Oi = Os.
 */
#include "anysl.h"

surface wood(
    uniform float Ka = 1;
    uniform float Kd = 0.75;
    uniform float Ks = 0.4;
    uniform float roughness = 0.1;
    uniform color specularcolor = 1;
    uniform float ringscale = 8;     /* rings per unit distance from the z axis */
    uniform float grainscale = 48;   /* grain frequency across the rings (1/32 along z) */
    uniform color lightwood = color (0.70, 0.45, 0.22);
    uniform color darkwood = color (0.30, 0.15, 0.06);)
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);

    float x = xcomp(P);
    float y = ycomp(P);
    float z = zcomp(P);
    float n1 = snoise(P * 2 + vector (0.375, 1.25, 2.625));
    float r = ringscale * sqrt(x * x + y * y) + 1.5 * n1;
    float f = r - floor(r);
    float ring = smoothstep(0, 0.8, f) - smoothstep(0.83, 1, f);
    float n2 = snoise(point (grainscale * x, grainscale * y, (grainscale / 32) * z));
    float grain = 0.8 + 0.2 * n2;
    color Ct = (lightwood + (darkwood - lightwood) * ring) * grain;

    Oi = Os;
    Ci = Os * anysl_plastic(Nf, V, Ct, Ka, Kd, Ks, roughness, specularcolor);
}
