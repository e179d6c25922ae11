// test: the globals P, N and Ng of the harness
// expect: p = 0.5, 0.5, 0
// expect: w = 0, 0, 2
surface t_global_P_N(output varying point p = 0; output varying vector w = 0;)
{
    p = P;
    w = N + Ng;
}
