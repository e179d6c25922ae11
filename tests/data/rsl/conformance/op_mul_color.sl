// test: color * color is componentwise
// expect: Ci = 2, 0.5, -3
surface t_op_mul_color()
{
    Ci = color(0.5, 2, 3) * color(4, 0.25, -1);
}
