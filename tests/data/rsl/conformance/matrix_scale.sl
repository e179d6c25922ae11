// test: scale(m, s) with m the identity
// expect: p = 2, 3, 4
surface t_matrix_scale(output varying point p = 0;)
{
    matrix m = scale(matrix 1, point(2, 3, 4));
    p = transform(m, point(1, 1, 1));
}
