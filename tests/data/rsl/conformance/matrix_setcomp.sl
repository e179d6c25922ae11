// test: setcomp(m, row, col, value)
// expect: p = 6, 2, 1
surface t_matrix_setcomp(output varying point p = 0;)
{
    matrix m = 1;
    setcomp(m, 3, 0, 5);
    setcomp(m, 1, 1, 2);
    p = transform(m, point(1, 1, 1));
}
