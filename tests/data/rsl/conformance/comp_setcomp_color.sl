// test: setcomp(color, i, value)
// expect: Ci = 0, 0.5, 0.25
surface t_comp_setcomp_color()
{
    color a = 0;
    setcomp(a, 1, 0.5);
    setcomp(a, 2, 0.25);
    Ci = a;
}
