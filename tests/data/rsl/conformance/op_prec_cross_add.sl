// test: ^ binds tighter than +: a + b ^ c is a + (b ^ c)
// expect: w = 1, 8, -2
surface t_op_prec_cross_add(output varying vector w = 0;)
{
    vector a = vector(1, 2, 3);
    vector b = vector(4, 5, 6);
    vector c = vector(1, 0, 0);
    w = a + b ^ c;
}
