/*
 * workload_checker — shading workload §5(b), the .sl twin of WorkloadChecker
 * (shaders/src/workload/surfaces.rs): a solid 3D checker on object-space P,
 *   q = floor(f·x) + floor(f·y) + floor(f·z),  Cs' = (q odd) ? oddcolor : evencolor
 * under the §3 model. q is a small integer, exact in float; RSL's mod is floored, so
 * mod(q, 2) == 1 exactly when q is odd, negative q included (the Rust tests q & 1).
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

surface workload_checker(
    uniform float frequency = 4;    /* checks per unit length along each axis */
    uniform color oddcolor = color (0.10, 0.20, 0.45);
    uniform color evencolor = color (0.90, 0.85, 0.70);
    uniform float Ka = 1.0;
    uniform float Kd = 0.80;
    uniform float Ks = 0.30;
    uniform float roughness = 0.08;)
{
    float q = floor(frequency * xcomp(P)) + floor(frequency * ycomp(P)) + floor(frequency * zcomp(P));
    color Ct = (mod(q, 2) == 1) ? oddcolor : evencolor;
    Oi = Os;
    Ci = workload_illum(Ct, Ka, Kd, Ks, roughness);
}
