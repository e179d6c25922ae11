// test: illuminance around -N sees no light
// expect: r = 0
surface t_illum_back(output varying float r = 0;)
{
    r = 0;
    illuminance(P, -N, PI / 2) {
        r += 1;
    }
}
