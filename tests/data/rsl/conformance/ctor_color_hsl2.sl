// test: color "hsl" (0.1, 0.8, 0.7)
// expect: Ci = 0.94, 0.748, 0.46
surface t_ctor_color_hsl2()
{
    Ci = color "hsl" (0.1, 0.8, 0.7);
}
