// test: mix on points
// expect: p = 1, 2, 4
surface t_math_mix_point(output varying point p = 0;)
{
    p = mix(point(0, 0, 0), point(2, 4, 8), s);
}
