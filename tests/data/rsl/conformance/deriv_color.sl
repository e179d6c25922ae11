// test: Du of a color built from s and t
// expect: Ci = 2, 0, 0.5
surface t_deriv_color()
{
    Ci = Du(color(s * 2, t, s * t));
}
