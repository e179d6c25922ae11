// test: Du of a polynomial in u: Du(u*u*u) = 3u^2; Dv(t*t) = 2t
// expect: r = 0.75
// expect: g = 1
surface t_deriv_poly(output varying float r = 0; output varying float g = 0;)
{
    r = Du(u * u * u);
    g = Dv(t * t);
}
