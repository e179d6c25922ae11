// test: comp(m, row, col) reads row-major elements
// expect: r = 713
surface t_matrix_comp(output varying float r = 0;)
{
    matrix m = (1, 2, 3, 4,  5, 6, 7, 8,  9, 10, 11, 12,  13, 14, 15, 16);
    r = comp(m, 1, 2) * 100 + comp(m, 3, 0);
}
