// test: arithmetic binds tighter than comparison
// expect: r = 1
surface t_op_cmp_arith_precedence(output varying float r = 0;)
{
    r = (1 + 2 * 3 == 7) ? 1 : 0;
}
