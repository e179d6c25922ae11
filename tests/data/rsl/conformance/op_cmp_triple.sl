// test: == and != on points and colors
// expect: r = 1
// expect: g = 0
surface t_op_cmp_triple(output varying float r = 0; output varying float g = 0;)
{
    r = (P == point(0.5, 0.5, 0)) ? 1 : 0;
    g = (Cs != color(1, 1, 1)) ? 1 : 0;
}
