// test: color * float and float * color
// expect: Ci = 0.2, 0.4, 0.6
surface t_op_color_float()
{
    color a = color(0.2, 0.4, 0.6) * 0.5;
    Ci = 2 * a;
}
