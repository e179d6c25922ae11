// test: += on a float
// expect: r = 3.5
// expect: Ci = 3.5, 3.5, 3.5
surface t_op_assign_add(output varying float r = 0;)
{
    r = 1;
    r += 2.5;
    Ci = r;
}
