// test: a float is promoted to a triple in a binary operation
// expect: Ci = 0.75, 0.5, 0.25
surface t_op_float_promote()
{
    Ci = 1 - color(0.25, 0.5, 0.75);
}
