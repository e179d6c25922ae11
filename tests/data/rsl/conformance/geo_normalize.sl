// test: normalize
// expect: w = 0.6, 0, -0.8
surface t_geo_normalize(output varying vector w = 0;)
{
    w = normalize(vector(3, 0, -4));
}
