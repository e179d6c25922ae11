// test: *= on a float
// expect: r = -6
// expect: Ci = -6, -6, -6
surface t_op_assign_mul(output varying float r = 0;)
{
    r = 1.5;
    r *= -4;
    Ci = r;
}
