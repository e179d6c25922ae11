// test: ?: on colors
// expect: Ci = 0.1, 0.2, 0.3
surface t_op_ternary_color()
{
    Ci = (t > 0.25) ? color(0.1, 0.2, 0.3) : color(1, 1, 1);
}
