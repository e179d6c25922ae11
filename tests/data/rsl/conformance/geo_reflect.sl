// test: reflect(I, N)
// expect: w = 1, 1, 0
surface t_geo_reflect(output varying vector w = 0;)
{
    w = reflect(vector(1, -1, 0), normal(0, 1, 0));
}
