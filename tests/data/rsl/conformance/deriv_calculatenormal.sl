// test: calculatenormal(P) = Du(P) x Dv(P)
// expect: w = 0, 0, 1
surface t_deriv_calculatenormal(output varying vector w = 0;)
{
    w = calculatenormal(P);
}
