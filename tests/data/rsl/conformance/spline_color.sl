// test: spline over color knots
// expect: Ci = 0.5984, 0.468, 0.912
surface t_spline_color()
{
    Ci = spline(0.6, color(0, 0, 0), color(0.2, 0.4, 0.1), color(0.5, 0.5, 0.9), color(1, 0.3, 0.6), color(0.8, 0.8, 0.2));
}
