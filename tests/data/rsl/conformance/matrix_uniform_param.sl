// test: matrix shader parameter with a default
// expect: p = 1, 0.5, 0
surface t_matrix_uniform_param(matrix xf = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0.5, 0, 0, 1); output varying point p = 0;)
{
    p = transform(xf, P);
}
