// test: derivatives of a constant are zero
// expect: r = 0
// expect: g = 0
surface t_deriv_const(output varying float r = 0; output varying float g = 0;)
{
    r = Du(3.5);
    g = Dv(2 * PI);
}
