// test: unary minus binds tighter than binary operators
// expect: r = -5
// expect: g = 13
// expect: Ci = -5, 13, 0
surface t_op_neg_precedence(output varying float r = 0; output varying float g = 0;)
{
    float a = 3;
    r = -a * 2 + 1;
    g = 10 - -a;
    Ci = color(r, g, 0);
}
