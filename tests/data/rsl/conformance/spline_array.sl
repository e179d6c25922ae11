// test: spline with the knots in a float array
// expect: r = 2.917
surface t_spline_array(output varying float r = 0;)
{
    float k[6] = {0, 1, 3, 2, 5, 4};
    r = spline(0.3, k);
}
