// test: -= on a float
// expect: r = -1.5
// expect: Ci = -1.5, -1.5, -1.5
surface t_op_assign_sub(output varying float r = 0;)
{
    r = 1;
    r -= 2.5;
    Ci = r;
}
