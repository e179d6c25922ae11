// test: /= on a float
// expect: r = 0.75
// expect: Ci = 0.75, 0.75, 0.75
surface t_op_assign_div(output varying float r = 0;)
{
    r = 3;
    r /= 4;
    Ci = r;
}
