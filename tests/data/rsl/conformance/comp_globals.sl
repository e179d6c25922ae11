// test: components of the globals P and I
// expect: r = 1
// expect: g = -3
surface t_comp_globals(output varying float r = 0; output varying float g = 0;)
{
    r = xcomp(P) + ycomp(P);
    g = zcomp(I);
}
