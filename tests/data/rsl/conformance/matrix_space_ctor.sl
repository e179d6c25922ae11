// test: matrix "world" (16 numbers) parses (identity space in the harness)
// expect: p = 1, 2, 3
surface t_matrix_space_ctor(output varying point p = 0;)
{
    matrix m = matrix "world" (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  1, 2, 3, 1);
    p = transform(m, point(0, 0, 0));
}
