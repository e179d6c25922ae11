/*
 * workload_granite — shading workload §5(d), the .sl twin of WorkloadGranite
 * (shaders/src/workload/surfaces.rs): turbulence of Q = frequency·P + offset,
 *   turb = Σ_{o=0..5} |snoise(2^o·Q)| / 2^o,  t = clamp(contrast·turb, 0, 1)
 *   Cs'  = darkcolor + t·(lightcolor - darkcolor), the §3 model.
 * The octave loop is uniform with a fixed trip count; dividing by a power of two is exact.
 * snoise(point) is the workload's noise (see workload/wood.sl).
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

surface workload_granite(
    uniform float frequency = 4;    /* scale of P in the noise domain */
    uniform vector offset = vector (1.5, 0.75, 2.25);
    uniform float contrast = 1.5;   /* gain from turbulence to the dark-light mix */
    uniform color darkcolor = color (0.20, 0.18, 0.17);
    uniform color lightcolor = color (0.95, 0.92, 0.88);
    uniform float Ka = 1.0;
    uniform float Kd = 0.80;
    uniform float Ks = 0.20;
    uniform float roughness = 0.08;)
{
    point Q = P * frequency + offset;
    float turb = 0;
    uniform float o;
    uniform float s = 1;
    for (o = 0; o < 6; o += 1) {
        turb += abs(snoise(Q * s)) / s;
        s *= 2;
    }
    float t = clamp(contrast * turb, 0, 1);
    color Ct = darkcolor + (lightcolor - darkcolor) * t;
    Oi = Os;
    Ci = workload_illum(Ct, Ka, Kd, Ks, roughness);
}
