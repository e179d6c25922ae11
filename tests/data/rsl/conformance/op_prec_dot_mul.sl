// test: . binds tighter than *: a * b . c is a * (b . c)
// expect: w = 4, 8, 12
surface t_op_prec_dot_mul(output varying vector w = 0;)
{
    vector a = vector(1, 2, 3);
    vector b = vector(4, 5, 6);
    vector c = vector(1, 0, 0);
    w = a * b . c;
}
