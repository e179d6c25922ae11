// test: mix(a, b, t) for a float
// expect: r = 3
surface t_math_mix(output varying float r = 0;)
{
    r = mix(2, 6, 0.25);
}
