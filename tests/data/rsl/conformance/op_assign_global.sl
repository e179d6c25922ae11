// test: assigning globals Ci and Oi
// expect: Oi = 0.5, 0.25, 1
// expect: Ci = 1, 0.5, 2
surface t_op_assign_global()
{
    Oi = color(0.5, 0.25, 1);
    Ci = Oi * 2;
}
