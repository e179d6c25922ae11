// test: a user function on colors
// expect: Ci = 0.6, 0.7, 0.8
color tint(color c; float k)
{
    return c * k + (1 - k);
}

surface t_func_color()
{
    Ci = tint(color(0.2, 0.4, 0.6), 0.5);
}
