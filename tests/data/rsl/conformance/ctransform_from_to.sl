// test: ctransform("hsl", "rgb", c) converts hsl to rgb
// expect: c = 0.2, 0.36, 0.6
surface t_ctransform_from_to(output varying color c = 0;)
{
    c = ctransform("hsl", "rgb", color(0.6, 0.5, 0.4));
}
