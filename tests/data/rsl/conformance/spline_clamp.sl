// test: the spline parameter is clamped to [0, 1]
// expect: r = 1
// expect: g = 5
surface t_spline_clamp(output varying float r = 0; output varying float g = 0;)
{
    r = spline(-0.5, 0, 1, 3, 2, 5, 4);
    g = spline(1.5, 0, 1, 3, 2, 5, 4);
}
