// test: comp(color, i)
// expect: r = 80.25
surface t_comp_color(output varying float r = 0;)
{
    color a = color(0.25, 0.5, 0.75);
    r = comp(a, 0) + 10 * comp(a, 1) + 100 * comp(a, 2);
}
