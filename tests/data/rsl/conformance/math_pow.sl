// test: pow
// expect: r = 1024
// expect: g = 0.176776695
// tol: 0.0001
surface t_math_pow(output varying float r = 0; output varying float g = 0;)
{
    r = pow(2, 10);
    g = pow(0.5, 2.5);
}
