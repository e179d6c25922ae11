// test: x ^ y = z and y ^ x = -z
// expect: w = 0, 0, 1
// expect: p = 0, 0, -1
surface t_op_cross_axes(output varying vector w = 0; output varying point p = 0;)
{
    w = vector(1, 0, 0) ^ vector(0, 1, 0);
    p = point(vector(0, 1, 0) ^ vector(1, 0, 0));
}
