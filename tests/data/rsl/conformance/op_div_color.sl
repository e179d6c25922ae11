// test: color / color is componentwise
// expect: Ci = 0.25, 1.5, 0.5
surface t_op_div_color()
{
    Ci = color(1, 3, 5) / color(4, 2, 10);
}
