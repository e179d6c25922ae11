// test: spline("linear") interpolates the inner knots linearly
// expect: r = 2.8
// expect: g = 2.125
surface t_spline_linear(output varying float r = 0; output varying float g = 0;)
{
    r = spline("linear", 0.3, 0, 1, 3, 2, 5, 4);
    g = spline("linear", 0.625, 0, 1, 3, 2, 5, 4);
}
