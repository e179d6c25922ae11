// test: dPdu and dPdv
// expect: w = 1, 0, 0
// expect: p = 0, 1, 0
surface t_global_dPdu(output varying vector w = 0; output varying point p = 0;)
{
    w = dPdu;
    p = point dPdv;
}
