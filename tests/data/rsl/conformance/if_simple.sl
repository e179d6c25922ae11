// test: if without else
// expect: r = 2
surface t_if_simple(output varying float r = 0;)
{
    r = 1;
    if (s > 0.25)
        r = 2;
    if (s > 0.75)
        r = 3;
}
