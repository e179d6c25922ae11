// test: += and *= on a point
// expect: p = 1, 1, 1
surface t_op_assign_ops_point(output varying point p = 0;)
{
    p = point(1, 2, 3);
    p += vector(1, 0, -1);
    p *= 0.5;
}
