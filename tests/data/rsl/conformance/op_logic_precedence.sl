// test: && binds tighter than ||
// expect: r = 1
// expect: Ci = 1, 1, 1
surface t_op_logic_precedence(output varying float r = 0;)
{
    r = (1 < 2 || 2 < 1 && 3 < 2) ? 1 : 0;
    Ci = r;
}
