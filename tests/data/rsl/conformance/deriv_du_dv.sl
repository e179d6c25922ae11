// test: Du(u) = 1, Dv(v) = 1, Du(v) = 0, Dv(u) = 0
// expect: r = 11
// expect: g = 0
surface t_deriv_du_dv(output varying float r = 0; output varying float g = 0;)
{
    r = Du(u) + 10 * Dv(v);
    g = Du(v) + 10 * Dv(u);
}
