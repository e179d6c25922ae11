// test: color "hsv" hue 1/3 is green
// expect: Ci = 0, 0.5, 0
surface t_ctor_color_hsv_third()
{
    Ci = color "hsv" (1/3, 1, 0.5);
}
