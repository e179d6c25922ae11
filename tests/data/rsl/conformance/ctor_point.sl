// test: point(x, y, z) and a float promoted to a point
// expect: p = 1, 2, 3
// expect: w = 2, 2, 2
surface t_ctor_point(output varying point p = 0; output varying vector w = 0;)
{
    p = point(1, 2, 3);
    w = vector 2;
}
