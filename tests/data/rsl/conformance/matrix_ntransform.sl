// test: ntransform(m, n) uses the inverse transpose
// expect: w = 0.5, 0.25, 1
surface t_matrix_ntransform(output varying vector w = 0;)
{
    matrix m = (2, 0, 0, 0,  0, 4, 0, 0,  0, 0, 1, 0,  5, 6, 7, 1);
    w = ntransform(m, normal(1, 1, 1));
}
