// test: ?: picks by a relation
// expect: r = 2
// expect: g = 3
// expect: Ci = 2, 3, 0
surface t_op_ternary(output varying float r = 0; output varying float g = 0;)
{
    r = (s < 0.75) ? 2 : 3;
    g = (s > 0.75) ? 2 : 3;
    Ci = color(r, g, 0);
}
