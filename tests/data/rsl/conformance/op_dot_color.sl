// test: dot products apply to colors too
// expect: r = 4.5
// expect: Ci = 4.5, 4.5, 4.5
surface t_op_dot_color(output varying float r = 0;)
{
    r = color(0.5, 1, 2) . color(2, 3, 0.25);
    Ci = r;
}
