// test: spline("hermite"): knots are point, tangent, point, tangent, ...
// expect: r = 1.392
// expect: g = 1.625
surface t_spline_hermite(output varying float r = 0; output varying float g = 0;)
{
    r = spline("hermite", 0.3, 0, 1, 2, 0, 1, -1);
    g = spline("hermite", 0.75, 0, 1, 2, 0, 1, -1);
}
