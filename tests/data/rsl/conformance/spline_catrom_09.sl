// test: spline (default catmull-rom) of 6 float knots at 0.9
// expect: r = 4.268
surface t_spline_catrom_09(output varying float r = 0;)
{
    r = spline(0.9, 0, 1, 3, 2, 5, 4);
}
