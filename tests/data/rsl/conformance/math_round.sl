// test: round to the nearest integer
// expect: r = 32
// expect: g = -3
surface t_math_round(output varying float r = 0; output varying float g = 0;)
{
    r = round(2.4) + 10 * round(2.6);
    g = round(-2.6);
}
