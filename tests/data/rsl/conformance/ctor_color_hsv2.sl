// test: color "hsv" (0.6, 0.5, 0.8)
// expect: Ci = 0.4, 0.56, 0.8
surface t_ctor_color_hsv2()
{
    Ci = color "hsv" (0.6, 0.5, 0.8);
}
