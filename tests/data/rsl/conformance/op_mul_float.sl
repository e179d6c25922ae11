// test: float multiplication
// expect: r = -3.75
// expect: Ci = -3.75, -3.75, -3.75
surface t_op_mul_float(output varying float r = 0;)
{
    r = 1.5 * -2.5;
    Ci = r;
}
