// test: <= on floats
// expect: r = 1
// expect: g = 0
surface t_op_cmp_le(output varying float r = 0; output varying float g = 0;)
{
    r = (2 <= 2) ? 1 : 0;
    g = (3 <= 2) ? 1 : 0;
}
