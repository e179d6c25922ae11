/*
 * anysl.h — helpers shared by the RSL ports of the anysl classic surfaces
 * (shaders/rsl/*.sl). Each helper mirrors a piece of shaders/src/common.rs
 * operation for operation, so a compiled .sl matches the hand-written Rust.
 */
#ifndef ANYSL_H
#define ANYSL_H 1

/*
 * A square wave of period 1 — 0 on [0, 1/2), 1 on [1/2, 1) — box-filtered with
 * filterstep over the pixel footprint of x (common.rs `filtered_square`). Each of
 * the two edges of a period is filtered by the filterstep nearer to it; without
 * derivatives it is exactly step(0.5, mod(x, 1)).
 */
float anysl_filtered_square(float x)
{
    float xm = mod(x, 1);
    /* The falling edge sits at the integers: measure from there, negative just below. */
    float from_int = (xm >= 0.5) ? xm - 1 : xm;
    float rising = filterstep(0.5, xm);
    float falling = 1 - filterstep(0, from_int);
    return (abs(xm - 0.5) < 0.25) ? rising : falling;
}

/*
 * The matte illumination model (common.rs `Finish::matte_part`):
 *   Ct·(Ka·ambient() + Kd·diffuse(Nf)), not yet multiplied by Os.
 */
color anysl_matte(normal Nf; color Ct; uniform float Ka, Kd)
{
    return Ct * (Ka * ambient() + Kd * diffuse(Nf));
}

/*
 * The plastic illumination model (common.rs `Finish::plastic`): the matte part plus
 *   specularcolor·Ks·specular(Nf, V, roughness),
 * not yet multiplied by Os. Ks is uniform: with Ks == 0 the specular light loop is
 * skipped (a branch on a parameter, not on a point). The matte part is written out rather
 * than called: the JIT fuses the `specular` loop with the `ambient`/`diffuse` loop that
 * follows it within one function body.
 */
color anysl_plastic(normal Nf; vector V; color Ct;
                    uniform float Ka, Kd, Ks, roughness;
                    uniform color specularcolor)
{
    color spec = 0;
    if (Ks != 0)
        spec = specular(Nf, V, roughness);
    return Ct * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * spec;
}

#endif /* ANYSL_H */
