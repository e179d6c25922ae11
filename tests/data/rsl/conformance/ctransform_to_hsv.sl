// test: ctransform("hsv", c) converts rgb to hsv
// expect: c = 0.611111111, 0.75, 0.8
surface t_ctransform_to_hsv(output varying color c = 0;)
{
    c = ctransform("hsv", color(0.2, 0.4, 0.8));
}
