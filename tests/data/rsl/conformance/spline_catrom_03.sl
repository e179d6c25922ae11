// test: spline (default catmull-rom) of 6 float knots at 0.3
// expect: r = 2.917
surface t_spline_catrom_03(output varying float r = 0;)
{
    r = spline(0.3, 0, 1, 3, 2, 5, 4);
}
