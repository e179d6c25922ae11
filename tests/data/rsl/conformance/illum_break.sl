// test: break inside illuminance stops visiting lights
// expect: r = 1
surface t_illum_break(output varying float r = 0;)
{
    r = 0;
    illuminance(P) {
        r += 1;
        break;
    }
}
