// test: dot product of a point and a normal
// expect: r = 0
// expect: Ci = 0, 0, 0
surface t_op_dot_mixed(output varying float r = 0;)
{
    r = point(0.5, 0.25, 2) . normal(2, 4, -1);
    Ci = r;
}
