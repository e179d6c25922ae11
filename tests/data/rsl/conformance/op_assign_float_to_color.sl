// test: assigning a float to a color fills every component
// expect: Ci = 0.25, 0.25, 0.25
surface t_op_assign_float_to_color()
{
    color a = 0.25;
    Ci = a;
}
