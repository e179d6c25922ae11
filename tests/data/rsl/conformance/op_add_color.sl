// test: color + color
// expect: Ci = 0.5, 0.7, 0.9
surface t_op_add_color()
{
    Ci = color(0.1, 0.2, 0.3) + color(0.4, 0.5, 0.6);
}
