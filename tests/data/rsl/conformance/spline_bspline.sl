// test: spline("bspline")
// expect: r = 2.54933333
// expect: g = 4.33333333
surface t_spline_bspline(output varying float r = 0; output varying float g = 0;)
{
    r = spline("bspline", 0.4, 0, 1, 3, 2, 5, 4);
    g = spline("bspline", 1, 0, 1, 3, 2, 5, 4);
}
