// test: exp
// expect: r = 4.48168907
// tol: 0.0001
surface t_math_exp(output varying float r = 0;)
{
    r = exp(1.5);
}
