/*
 * workload_plastic — shading workload §5(a) (shaders/assets/workload_ref/shading_workload.md),
 * the .sl twin of shaders/src/workload/surfaces.rs WorkloadPlastic: a constant surface colour
 * under the §3 model (Blinn exponent 1/roughness = 12.5).
 *   Ci = Cs'·(Ka·ambient() + Kd·diff) + Ks·spec, Oi = Os, Cs' = surfacecolor
 * Noise-free; the other three add a pattern for Cs'.
 */

/*
 * The illumination model of workload §3, written out (this file is self-contained, so that it
 * compiles from embedded text without an include path): the ambient light, then one light
 * loop over every light with L (surface to light, unnormalized) normalized. illum(P, N, V)
 * of §3 takes the unit normal and the unit vector to the eye of §2 as they are: N as given
 * (every hit faces the eye: no faceforward), V = -I; its result is Ci.
 */
color workload_illum(color Ct; uniform float Ka, Kd, Ks, roughness)
{
    normal Nn = N;
    vector V = -I;
    color diff = 0;
    color spec = 0;
    illuminance (P) {
        vector Ln = normalize(L);
        float ndl = Nn . Ln;
        float ndh = max(Nn . normalize(Ln + V), 0);
        diff += Cl * max(ndl, 0);
        spec += Cl * ((ndl > 0) ? pow(ndh, 1 / roughness) : 0);
    }
    return Ct * (Ka * ambient() + Kd * diff) + Ks * spec;
}

surface workload_plastic(
    uniform color surfacecolor = color (0.80, 0.25, 0.15);
    uniform float Ka = 1.0;
    uniform float Kd = 0.80;
    uniform float Ks = 0.50;
    uniform float roughness = 0.08;)
{
    Oi = Os;
    Ci = workload_illum(surfacecolor, Ka, Kd, Ks, roughness);
}
