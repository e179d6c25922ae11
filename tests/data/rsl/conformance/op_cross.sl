// test: ^ is the cross product
// expect: w = -3, 6, -3
// expect: Ci = -3, 6, -3
surface t_op_cross(output varying vector w = 0;)
{
    w = vector(1, 2, 3) ^ vector(4, 5, 6);
    Ci = color(xcomp(w), ycomp(w), zcomp(w));
}
