// test: log(x, base)
// expect: r = 3
// expect: g = 3
// tol: 0.0001
surface t_math_log_base(output varying float r = 0; output varying float g = 0;)
{
    r = log(8, 2);
    g = log(1000, 10);
}
