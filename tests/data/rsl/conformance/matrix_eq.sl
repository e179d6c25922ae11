// test: matrix == and !=
// expect: r = 1
// expect: g = 0
surface t_matrix_eq(output varying float r = 0; output varying float g = 0;)
{
    matrix a = 1;
    matrix b = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1);
    r = (a == b) ? 1 : 0;
    g = (a != b) ? 1 : 0;
}
