// test: a varying if inside illuminance
// expect: r = 101
surface t_illum_nested_if(output varying float r = 0;)
{
    r = 0;
    illuminance(P) {
        if (zcomp(L) > 4)
            r += 1;
        else
            r += 100;
    }
}
