// test: Deriv(num, den) = Du(num)/Du(den) + Dv(num)/Dv(den), dropping zero denominators
// expect: r = 0.75
// expect: g = 0
surface t_deriv_Deriv(output varying float r = 0; output varying float g = 0;)
{
    r = Deriv(u * u * u, u);
    g = Deriv(t, s);
}
