// test: color "hsv" (0.3, 0, 0.4)
// expect: Ci = 0.4, 0.4, 0.4
surface t_ctor_color_hsv_grey()
{
    Ci = color "hsv" (0.3, 0, 0.4);
}
