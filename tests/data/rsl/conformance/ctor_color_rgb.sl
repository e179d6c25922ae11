// test: color(r, g, b) and color "rgb" (r, g, b)
// expect: c = 0.25, 0.5, 1
// expect: Ci = 0.1, 0.2, 0.3
surface t_ctor_color_rgb(output varying color c = 0;)
{
    c = color "rgb" (0.25, 0.5, 1);
    Ci = color(0.1, 0.2, 0.3);
}
