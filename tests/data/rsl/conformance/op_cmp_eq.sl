// test: == on floats
// expect: r = 1
// expect: g = 0
surface t_op_cmp_eq(output varying float r = 0; output varying float g = 0;)
{
    r = (0.5 == s) ? 1 : 0;
    g = (0.25 == s) ? 1 : 0;
}
