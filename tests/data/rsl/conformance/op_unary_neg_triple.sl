// test: unary minus on a point and a color
// expect: p = -1, 2, -3
// expect: Ci = -0.5, 0.25, 0
surface t_op_unary_neg_triple(output varying point p = 0;)
{
    p = -point(1, -2, 3);
    Ci = -color(0.5, -0.25, 0);
}
