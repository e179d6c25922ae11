// test: float subtraction
// expect: r = -0.75
// expect: Ci = 0, -0.75, 0
surface t_op_sub_float(output varying float r = 0;)
{
    r = 1.5 - 2.25;
    Ci = color(0, r, 0);
}
