// test: += -= *= /= on a color, with color and float right-hand sides
// expect: Ci = 1, 1, 1
surface t_op_assign_ops_color()
{
    color a = color(1, 2, 3);
    a += color(1, 1, 1);
    a *= 2;
    a -= color(0, 1, 2);
    a /= color(4, 5, 6);
    Ci = a;
}
