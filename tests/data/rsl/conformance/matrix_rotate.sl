// test: rotate(m, angle, axis): PI/2 about z takes x to y
// expect: p = 0, 1, 0
surface t_matrix_rotate(output varying point p = 0;)
{
    matrix m = rotate(matrix 1, PI / 2, vector(0, 0, 1));
    p = transform(m, point(1, 0, 0));
}
