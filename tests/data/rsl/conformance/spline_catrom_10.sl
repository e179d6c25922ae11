// test: spline (default catmull-rom) of 6 float knots at 1
// expect: r = 5
surface t_spline_catrom_10(output varying float r = 0;)
{
    r = spline(1, 0, 1, 3, 2, 5, 4);
}
