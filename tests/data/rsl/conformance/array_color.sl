// test: array of colors
// expect: Ci = 0.5, 0.5, 1
surface t_array_color()
{
    color a[2] = {color(1, 0, 0), color(0, 0.5, 1)};
    Ci = a[0] * 0.5 + a[1];
}
