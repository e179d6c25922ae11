// test: a varying if assigns only where its relation holds
// expect: Ci = 0, 1, 0
surface t_if_varying_assign()
{
    color c = color(1, 0, 0);
    if (P . N < 0.5)
        c = color(0, 1, 0);
    else
        c = color(0, 0, 1);
    Ci = c;
}
