// test: matrix m = 2 has 2 on the diagonal; comp(m, row, col)
// expect: r = 4
// expect: g = 0
surface t_matrix_float(output varying float r = 0; output varying float g = 0;)
{
    matrix m = 2;
    r = comp(m, 0, 0) + comp(m, 3, 3);
    g = comp(m, 0, 1);
}
