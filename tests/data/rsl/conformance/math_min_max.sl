// test: min and max of two and of several floats
// expect: r = 29
// expect: g = 82
surface t_math_min_max(output varying float r = 0; output varying float g = 0;)
{
    r = min(3, -1) + 10 * max(3, -1);
    g = min(4, 2, 8, 3) + 10 * max(4, 2, 8, 3);
}
