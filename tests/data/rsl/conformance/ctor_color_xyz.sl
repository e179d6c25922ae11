// test: color "xyz" (X, Y, Z) converts CIE XYZ (D65, Rec. 709 primaries) to RGB
// expect: Ci = 0.25757458, 0.46793572, 0.1465277
surface t_ctor_color_xyz()
{
    Ci = color "xyz" (0.3, 0.4, 0.2);
}
