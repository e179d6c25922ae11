// test: > on floats
// expect: r = 1
// expect: g = 0
surface t_op_cmp_gt(output varying float r = 0; output varying float g = 0;)
{
    r = (2.5 > -1) ? 1 : 0;
    g = (-1 > 2.5) ? 1 : 0;
}
