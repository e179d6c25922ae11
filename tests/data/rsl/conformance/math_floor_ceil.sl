// test: floor and ceil, positive and negative
// expect: r = -28
// expect: g = -17
surface t_math_floor_ceil(output varying float r = 0; output varying float g = 0;)
{
    r = floor(2.5) + 10 * floor(-2.5);
    g = ceil(2.5) + 10 * ceil(-2.5);
}
