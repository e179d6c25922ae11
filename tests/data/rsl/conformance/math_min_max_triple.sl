// test: min and max on colors and points are componentwise
// expect: c = 0.1, 0.2, 0.5
// expect: p = 1, 5, 3
surface t_math_min_max_triple(output varying color c = 0; output varying point p = 0;)
{
    c = min(color(0.1, 0.9, 0.5), color(0.4, 0.2, 0.5));
    p = max(point(1, -2, 3), point(0, 5, -3));
}
