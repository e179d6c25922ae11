// test: sqrt
// expect: r = 1.41421356
// expect: g = 0.25
surface t_math_sqrt(output varying float r = 0; output varying float g = 0;)
{
    r = sqrt(2);
    g = sqrt(0.0625);
}
