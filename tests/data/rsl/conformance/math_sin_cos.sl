// test: sin and cos
// expect: r = 0.479425539
// expect: g = 0.877582562
surface t_math_sin_cos(output varying float r = 0; output varying float g = 0;)
{
    r = sin(0.5);
    g = cos(0.5);
}
