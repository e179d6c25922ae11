// test: unary minus on a float variable and on an expression
// expect: r = -2.5
// expect: g = 1.5
// expect: Ci = -2.5, 1.5, 0
surface t_op_neg_float(output varying float r = 0; output varying float g = 0;)
{
    float a = 2.5;
    r = -a;
    g = -(a - 4);
    Ci = color(r, g, 0);
}
