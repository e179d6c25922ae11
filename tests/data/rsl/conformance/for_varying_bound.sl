// test: a loop whose bound depends on a varying value
// expect: r = 5
surface t_for_varying_bound(output varying float r = 0;)
{
    float i;
    r = 0;
    for (i = 0; i < s * 10; i += 1)
        r += 1;
}
