// test: translate(m, t) with m the identity
// expect: p = 2, -1, 1.5
surface t_matrix_translate(output varying point p = 0;)
{
    matrix m = translate(matrix 1, vector(1, -2, 0.5));
    p = transform(m, point(1, 1, 1));
}
