// test: an assignment is an expression: a = b = value
// expect: r = 0.75
// expect: g = 0.75
// expect: Ci = 0.75, 0.75, 0
surface t_op_assign_chain(output varying float r = 0; output varying float g = 0;)
{
    r = g = 0.75;
    Ci = color(r, g, 0);
}
