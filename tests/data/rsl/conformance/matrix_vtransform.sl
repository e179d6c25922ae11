// test: vtransform(m, v) ignores the translation
// expect: w = 2, 3, 1
surface t_matrix_vtransform(output varying vector w = 0;)
{
    matrix m = (2, 0, 0, 0,  0, 3, 0, 0,  0, 0, 1, 0,  5, 6, 7, 1);
    w = vtransform(m, vector(1, 1, 1));
}
