// test: tan
// expect: r = 2.57215162
// tol: 0.0001
surface t_math_tan(output varying float r = 0;)
{
    r = tan(1.2);
}
