// test: continue 2 continues the outer loop
// expect: r = 3
surface t_loop_continue_2(output varying float r = 0;)
{
    float i, j;
    r = 0;
    for (i = 0; i < 3; i += 1) {
        for (j = 0; j < 3; j += 1) {
            if (j == 1)
                continue 2;
            r += 1;
        }
        r += 100;
    }
}
