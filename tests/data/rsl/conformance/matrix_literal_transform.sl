// test: matrix literal (16 numbers, translation in the last row) and transform(m, p)
// expect: p = 3, 4, 5
surface t_matrix_literal_transform(output varying point p = 0;)
{
    matrix m = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  2, 3, 4, 1);
    p = transform(m, point(1, 1, 1));
}
