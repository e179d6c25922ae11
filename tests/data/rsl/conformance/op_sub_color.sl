// test: color - color
// expect: Ci = 0.5, 0, -0.3
surface t_op_sub_color()
{
    Ci = color(0.9, 0.5, 0.3) - color(0.4, 0.5, 0.6);
}
