// test: C float suffixes on numbers are read as the number
// expect: Ci = 0.5, 1, 0.2
surface t_compat_float_suffix()
{
    Ci = color(0.5f, 1.f, 2e-1F);
}
