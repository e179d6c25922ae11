// test: if / else
// expect: r = 2
// expect: g = 1
surface t_if_else(output varying float r = 0; output varying float g = 0;)
{
    if (s < 0.25) r = 1; else r = 2;
    if (t < 0.75) g = 1; else g = 2;
}
