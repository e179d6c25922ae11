// test: color "YIQ" (Y, I, Q) converts NTSC YIQ to RGB
// expect: Ci = 0.56455, 0.50515, 0.30425
surface t_ctor_color_yiq()
{
    Ci = color "YIQ" (0.5, 0.1, -0.05);
}
