// test: float division
// expect: r = 1.75
// expect: Ci = 1.75, 1.75, 1.75
surface t_op_div_float(output varying float r = 0;)
{
    r = 7 / 4;
    Ci = r;
}
