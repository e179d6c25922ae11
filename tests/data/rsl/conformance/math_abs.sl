// test: abs
// expect: r = 2.5
// expect: g = 1.25
// expect: Ci = 2.5, 0, 0
surface t_math_abs(output varying float r = 0; output varying float g = 0;)
{
    r = abs(-2.5);
    g = abs(1.25);
    Ci = color(r, 0, 0);
}
