// test: Du(P) = dPdu and Dv(P) = dPdv
// expect: w = 1, 0, 0
// expect: p = 0, 1, 0
surface t_deriv_P(output varying vector w = 0; output varying point p = 0;)
{
    w = Du(P);
    p = point Dv(P);
}
