// test: spline (default catmull-rom) of 6 float knots at 0
// expect: r = 1
surface t_spline_catrom_00(output varying float r = 0;)
{
    r = spline(0, 0, 1, 3, 2, 5, 4);
}
