// test: clamp on a color is componentwise
// expect: Ci = 0, 0.5, 1
surface t_math_clamp_color()
{
    Ci = clamp(color(-0.5, 0.5, 1.5), color(0, 0, 0), color(1, 1, 1));
}
