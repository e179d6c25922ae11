// test: illuminance(P) without an axis visits every non-ambient light
// expect: r = 2
surface t_illum_count(output varying float r = 0;)
{
    r = 0;
    illuminance(P) {
        r += 1;
    }
}
