// test: normalize of the global I
// expect: w = 0.162221421, 0.162221421, -0.973328527
surface t_geo_normalize_I(output varying vector w = 0;)
{
    w = normalize(I);
}
