// test: break under a varying condition
// expect: r = 4
surface t_loop_break_varying(output varying float r = 0;)
{
    float i;
    r = 0;
    for (i = 0; i < 10; i += 1) {
        if (i > s * 6)
            break;
        r += 1;
    }
}
