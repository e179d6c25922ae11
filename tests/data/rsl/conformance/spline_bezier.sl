// test: spline("bezier") over 7 knots (two segments)
// expect: r = 1.75
// expect: g = 4.592
surface t_spline_bezier(output varying float r = 0; output varying float g = 0;)
{
    r = spline("bezier", 0.25, 0, 1, 3, 2, 5, 4, 6);
    g = spline("bezier", 0.8, 0, 1, 3, 2, 5, 4, 6);
}
