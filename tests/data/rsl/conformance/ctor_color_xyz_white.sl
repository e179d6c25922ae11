// test: color "xyz" of the rgb white point is white (tolerance for the matrix rounding)
// expect: Ci = 0.999999905, 1.00000015, 0.999999977
// tol: 0.0001
surface t_ctor_color_xyz_white()
{
    Ci = color "xyz" (0.95047, 1.0000001, 1.08883);
}
