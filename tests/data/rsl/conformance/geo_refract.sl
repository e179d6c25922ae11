// test: refract(I, N, eta) by Snell's law
// expect: w = 0.471404521, 0, -0.881917104
surface t_geo_refract(output varying vector w = 0;)
{
    w = refract(normalize(vector(1, 0, -1)), normal(0, 0, 1), 1 / 1.5);
}
