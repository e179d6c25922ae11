// test: Du(u*v) = v, Dv(u*v) = u
// expect: r = 0.5
// expect: g = 2
surface t_deriv_product(output varying float r = 0; output varying float g = 0;)
{
    r = Du(u * v);
    g = Dv(u * v * 4);
}
