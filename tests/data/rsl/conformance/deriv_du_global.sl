// test: the globals du and dv (1 for a 1x1 grid)
// expect: r = 1
// expect: g = 1
surface t_deriv_du_global(output varying float r = 0; output varying float g = 0;)
{
    r = du;
    g = dv;
}
