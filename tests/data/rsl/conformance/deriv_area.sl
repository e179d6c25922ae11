// test: area(P) = |Du(P) du x Dv(P) dv| = du dv
// expect: r = 1
surface t_deriv_area(output varying float r = 0;)
{
    r = area(P);
}
