// test: inversesqrt
// expect: r = 0.957106781
surface t_math_inversesqrt(output varying float r = 0;)
{
    r = inversesqrt(16) + inversesqrt(2);
}
