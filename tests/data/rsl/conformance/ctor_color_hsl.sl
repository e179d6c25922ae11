// test: color "hsl" (0.6, 0.5, 0.4)
// expect: Ci = 0.2, 0.36, 0.6
surface t_ctor_color_hsl()
{
    Ci = color "hsl" (0.6, 0.5, 0.4);
}
