// test: pow of a colour by a float and by a colour, per component (PRMan, BMRT)
// expect: Ci = 0.5, 0.7071067811865476, 2
// expect: Oi = 4, 3, 2
surface t_compat_pow_color()
{
    Ci = pow(Cs * color(0.25, 0.5, 4), 0.5);
    Oi = pow(Cs * color(2, 3, 4), color(2, 1, 0.5));
}
