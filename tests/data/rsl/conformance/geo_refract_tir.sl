// test: refract under total internal reflection gives the zero vector
// expect: w = 0, 0, 0
surface t_geo_refract_tir(output varying vector w = 0;)
{
    w = refract(normalize(vector(1, 0, -0.2)), normal(0, 0, 1), 1.5);
}
