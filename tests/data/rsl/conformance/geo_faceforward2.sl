// test: faceforward(N, I) uses Ng as the reference
// expect: w = 0, -1, -1
surface t_geo_faceforward2(output varying vector w = 0;)
{
    w = faceforward(normal(0, 1, 1), vector(0, 0, 1));
}
