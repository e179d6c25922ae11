// test: * and / bind tighter than + and -; left-to-right grouping
// expect: r = 11
// expect: g = -1
// expect: Ci = 11, -1, 0
surface t_op_precedence_arith(output varying float r = 0; output varying float g = 0;)
{
    r = 2 + 3 * 4 - 6 / 2;
    g = 8 / 4 / 2 - 1 - 1;
    Ci = color(r, g, 0);
}
