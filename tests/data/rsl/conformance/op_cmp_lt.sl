// test: < on floats, true and false
// expect: r = 1
// expect: g = 0
// expect: Ci = 1, 0, 0
surface t_op_cmp_lt(output varying float r = 0; output varying float g = 0;)
{
    r = (1 < 2) ? 1 : 0;
    g = (2 < 2) ? 1 : 0;
    Ci = color(r, g, 0);
}
