// test: clamp below, inside and above
// expect: r = 205
surface t_math_clamp(output varying float r = 0;)
{
    r = clamp(-1, 0, 1) + 10 * clamp(0.5, 0, 1) + 100 * clamp(3, 0, 2);
}
