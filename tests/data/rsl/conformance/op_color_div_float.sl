// test: color / float
// expect: Ci = 0.25, 0.5, 0.75
surface t_op_color_div_float()
{
    Ci = color(1, 2, 3) / 4;
}
