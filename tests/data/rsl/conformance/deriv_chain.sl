// test: Du of sin(u) is cos(u) (chain rule)
// expect: r = 1.08060461
// tol: 0.0001
surface t_deriv_chain(output varying float r = 0;)
{
    r = Du(sin(u * 2));
}
