// test: illuminance(P, N, PI/2) visits the lights above the surface
// expect: r = 2
surface t_illum_hemisphere(output varying float r = 0;)
{
    r = 0;
    illuminance(P, N, PI / 2) {
        r += 1;
    }
}
