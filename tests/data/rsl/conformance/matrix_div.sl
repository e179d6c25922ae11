// test: matrix / matrix is multiplication by the inverse; (a * b) / b == a
// expect: p = 2, 4, 6
surface t_matrix_div(output varying point p = 0;)
{
    matrix a = (1, 2, 0, 0,  0, 1, 0, 0,  0, 0, 2, 0,  1, 0, 0, 1);
    matrix b = (0, 1, 0, 0,  -1, 0, 0, 0,  0, 0, 1, 0,  0, 3, 0, 1);
    p = transform((a * b) / b, point(1, 2, 3));
}
