// test: matrix * matrix (row vectors: transform by a then b)
// expect: p = -4, 5, 6
surface t_matrix_mul(output varying point p = 0;)
{
    matrix a = (1, 2, 0, 0,  0, 1, 0, 0,  0, 0, 2, 0,  1, 0, 0, 1);
    matrix b = (0, 1, 0, 0,  -1, 0, 0, 0,  0, 0, 1, 0,  0, 3, 0, 1);
    p = transform(a * b, point(1, 2, 3));
}
