// test: atan with one argument
// expect: r = 1.10714872
surface t_math_atan1(output varying float r = 0;)
{
    r = atan(2);
}
