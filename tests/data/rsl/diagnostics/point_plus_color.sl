// error: binary operation between a point and a color is illegal
// at: 5:15
surface d_point_plus_color()
{
    point q = P + Cs;
    Ci = color(xcomp(q), 0, 0);
}
