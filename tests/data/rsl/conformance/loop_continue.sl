// test: continue skips to the next iteration
// expect: r = 6
surface t_loop_continue(output varying float r = 0;)
{
    float i;
    r = 0;
    for (i = 0; i < 6; i += 1) {
        if (mod(i, 2) == 1)
            continue;
        r += i;
    }
}
