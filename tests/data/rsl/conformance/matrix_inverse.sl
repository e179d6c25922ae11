// test: identity / m is the inverse of m
// expect: p = 3.6, 10.8, 13
surface t_matrix_inverse(output varying point p = 0;)
{
    matrix m = (2, 1, 0, 0,  1, 3, 0, 0,  0, 0, 4, 1,  0, 0, 2, 5);
    matrix one = 1;
    p = transform(one / m, point(1, 2, 3));
}
