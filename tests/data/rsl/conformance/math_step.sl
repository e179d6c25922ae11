// test: step(edge, x)
// expect: r = 110
// expect: g = 1
surface t_math_step(output varying float r = 0; output varying float g = 0;)
{
    r = step(0.5, 0.25) + 10 * step(0.5, 0.5) + 100 * step(0.5, 0.75);
    g = step(s, 0.5);
}
