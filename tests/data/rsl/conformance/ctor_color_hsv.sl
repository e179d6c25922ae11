// test: color "hsv" (0, 1, 1)
// expect: Ci = 1, 0, 0
surface t_ctor_color_hsv()
{
    Ci = color "hsv" (0, 1, 1);
}
