// test: float addition
// expect: r = 3.75
// expect: Ci = 3.75, 0, 0
surface t_op_add_float(output varying float r = 0;)
{
    r = 1.5 + 2.25;
    Ci = color(r, 0, 0);
}
