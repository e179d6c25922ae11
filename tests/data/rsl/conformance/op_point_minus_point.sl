// test: point - point gives a vector
// expect: w = 0.5, -2, 4
// expect: Ci = 0.5, -2, 4
surface t_op_point_minus_point(output varying vector w = 0;)
{
    point a = point(1, 2, 3);
    point b = point(0.5, 4, -1);
    w = a - b;
    Ci = color(xcomp(w), ycomp(w), zcomp(w));
}
