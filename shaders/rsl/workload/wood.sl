/*
 * workload_wood — shading workload §5(c), the .sl twin of WorkloadWood
 * (shaders/src/workload/surfaces.rs): rings around the z axis perturbed by noise, and grain:
 *   r     = ringscale·sqrt(x² + y²) + 1.5·snoise(2P + (0.375, 1.25, 2.625))
 *   ring  = smoothstep(0, 0.8, f) - smoothstep(0.83, 1, f),  f = r - floor(r)
 *   grain = 0.8 + 0.2·snoise(48x, 48y, 1.5z)
 *   Cs'   = (lightwood + ring·(darkwood - lightwood))·grain, the §3 model.
 * snoise(point) is the workload's noise (§4): the same Perlin noise with the table-free hash,
 * clamped to [-1, 1], which is the identity at every input of the workload (checked by
 * tests/tests/workload.rs snoise_is_the_workload_noise_at_every_input).
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

surface workload_wood(
    uniform float ringscale = 8;    /* rings per unit distance from the z axis */
    uniform color lightwood = color (0.70, 0.45, 0.22);
    uniform color darkwood = color (0.30, 0.15, 0.06);
    uniform float Ka = 1.0;
    uniform float Kd = 0.75;
    uniform float Ks = 0.40;
    uniform float roughness = 0.08;)
{
    float x = xcomp(P);
    float y = ycomp(P);
    float z = zcomp(P);
    float n1 = snoise(point (2 * x + 0.375, 2 * y + 1.25, 2 * z + 2.625));
    float r = ringscale * sqrt(x * x + y * y) + 1.5 * n1;
    float f = r - floor(r);
    float ring = smoothstep(0, 0.8, f) - smoothstep(0.83, 1.0, f);
    float n2 = snoise(point (48 * x, 48 * y, 1.5 * z));
    float grain = 0.8 + 0.2 * n2;
    color Ct = (lightwood + (darkwood - lightwood) * ring) * grain;
    Oi = Os;
    Ci = workload_illum(Ct, Ka, Kd, Ks, roughness);
}
