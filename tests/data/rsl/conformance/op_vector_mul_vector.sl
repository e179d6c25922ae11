// test: vector * vector is componentwise
// expect: w = 2, -6, 2
surface t_op_vector_mul_vector(output varying vector w = 0;)
{
    w = vector(1, -2, 4) * vector(2, 3, 0.5);
}
