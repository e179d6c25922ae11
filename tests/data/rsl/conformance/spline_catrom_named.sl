// test: spline("catmull-rom", ...) equals the default basis
// expect: r = 2.156
// expect: g = 2.156
surface t_spline_catrom_named(output varying float r = 0; output varying float g = 0;)
{
    r = spline("catmull-rom", 0.7, 0, 1, 3, 2, 5, 4);
    g = spline(0.7, 0, 1, 3, 2, 5, 4);
}
