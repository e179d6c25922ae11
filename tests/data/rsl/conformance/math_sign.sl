// test: sign of negative, zero and positive
// expect: r = -99
surface t_math_sign(output varying float r = 0;)
{
    r = sign(-3) * 100 + sign(0) * 10 + sign(0.5);
}
