// test: mod(a, b) is in [0, b) also for negative a
// expect: r = 1.5
// expect: g = 1.5
surface t_math_mod(output varying float r = 0; output varying float g = 0;)
{
    r = mod(7.5, 2);
    g = mod(-0.5, 2);
}
