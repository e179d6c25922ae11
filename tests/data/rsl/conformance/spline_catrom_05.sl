// test: spline (default catmull-rom) of 6 float knots at 0.5
// expect: r = 2.4375
surface t_spline_catrom_05(output varying float r = 0;)
{
    r = spline(0.5, 0, 1, 3, 2, 5, 4);
}
