// test: indexing with a varying float (truncated)
// expect: r = 30
surface t_array_varying_index(output varying float r = 0;)
{
    float a[4] = {10, 20, 30, 40};
    r = a[s * 4 + 0.25];
}
