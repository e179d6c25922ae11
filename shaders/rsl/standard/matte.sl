/*
 * matte — RenderMan Interface 3.2 standard surface: an ideal diffuse (Lambertian)
 * reflector.
 *   Oi = Os, Ci = Os·Cs·(Ka·ambient() + Kd·diffuse(Nf))
 */
surface matte(float Ka = 1, Kd = 1;)
{
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Kd * diffuse(Nf));
}
