// test: determinant(m)
// expect: r = 90
surface t_matrix_determinant(output varying float r = 0;)
{
    matrix m = (2, 1, 0, 0,  1, 3, 0, 0,  0, 0, 4, 1,  0, 0, 2, 5);
    r = determinant(m);
}
