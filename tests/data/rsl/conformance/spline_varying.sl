// test: spline at a varying parameter (s)
// expect: r = 2.52083333
surface t_spline_varying(output varying float r = 0;)
{
    r = spline("bspline", s, 0, 1, 3, 2, 5, 4);
}
