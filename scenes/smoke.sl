/*
 * smoke — a ray-marched volume: the segment from E to P is cut into steps of at most
 * `stepsize`; each step's density is `density` times a noise of its midpoint (in world
 * space, scaled by `frequency`, blended in by `noisiness`), and it absorbs and glows with
 * `smokecolor` by the exact exponential of its optical depth, front to back. With
 * `noisiness` 0 the smoke is uniform: what arrives keeps exp(-density * |I|).
 */
volume smoke(float density = 0.5, stepsize = 0.1, frequency = 2, noisiness = 1;
             color smokecolor = 1;)
{
    float len = length(I);
    float steps = clamp(ceil(len / max(stepsize, 1e-3)), 1, 256);
    float dt = len / steps;
    vector dir = len > 0 ? I / len : vector(0, 0, 1);
    float through = 1;
    color glow = 0;
    float i;
    for (i = 0; i < steps; i += 1) {
        point Q = E + dir * ((i + 0.5) * dt);
        float wisp = mix(1, 2 * noise(Q * frequency), noisiness);
        float absorbed = 1 - exp(-density * max(wisp, 0) * dt);
        glow += through * absorbed * smokecolor;
        through *= 1 - absorbed;
    }
    Ci = glow + through * Ci;
    Oi = (1 - through) + through * Oi;
}
