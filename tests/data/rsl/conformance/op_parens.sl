// test: parentheses override precedence
// expect: r = -5
// expect: Ci = -5, -5, -5
surface t_op_parens(output varying float r = 0;)
{
    r = (2 + 3) * (4 - 6) / 2;
    Ci = r;
}
