// test: illuminance body never runs without lights
// lights: none
// expect: r = 0
// expect: Ci = 0.5, 0.5, 0.5
surface t_illum_count_none(output varying float r = 0;)
{
    r = 0;
    illuminance(P) {
        r += 1;
    }
    Ci = 0.5;
}
