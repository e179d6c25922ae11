// test: xcomp, ycomp, zcomp
// expect: r = 306.5
surface t_comp_xyz(output varying float r = 0;)
{
    point a = point(1.5, -2, 3.25);
    r = xcomp(a) + 10 * ycomp(a) + 100 * zcomp(a);
}
