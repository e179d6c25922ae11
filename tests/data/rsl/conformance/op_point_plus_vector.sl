// test: point + vector gives a point
// expect: p = 1.5, 1, 5
// expect: Ci = 1.5, 1, 5
surface t_op_point_plus_vector(output varying point p = 0;)
{
    p = point(1, 2, 3) + vector(0.5, -1, 2);
    Ci = color(xcomp(p), ycomp(p), zcomp(p));
}
