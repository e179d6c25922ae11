// test: Du(s) = 1 and Dv(t) = 1 (s = u, t = v)
// expect: r = 1
// expect: g = 1
surface t_deriv_st(output varying float r = 0; output varying float g = 0;)
{
    r = Du(s);
    g = Dv(t);
}
