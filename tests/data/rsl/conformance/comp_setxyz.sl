// test: setxcomp, setycomp, setzcomp
// expect: p = 7, -1, 0.5
surface t_comp_setxyz(output varying point p = 0;)
{
    p = point(1, 2, 3);
    setxcomp(p, 7);
    setycomp(p, -1);
    setzcomp(p, 0.5);
}
