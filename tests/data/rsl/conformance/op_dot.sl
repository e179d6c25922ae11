// test: . is the dot product of two vectors
// expect: r = 12
// expect: Ci = 12, 12, 12
surface t_op_dot(output varying float r = 0;)
{
    r = vector(1, 2, 3) . vector(4, -5, 6);
    Ci = r;
}
