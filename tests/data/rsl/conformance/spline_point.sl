// test: spline over point knots
// expect: p = 1.105, 0.742, -0.0735
surface t_spline_point(output varying point p = 0;)
{
    p = spline(0.35, point(0, 0, 0), point(1, 0, 0), point(1, 1, 0), point(0, 1, 1), point(0, 0, 1));
}
