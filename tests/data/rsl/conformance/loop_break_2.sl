// test: break 2 leaves two nested loops
// expect: r = 104
surface t_loop_break_2(output varying float r = 0;)
{
    float i, j;
    r = 0;
    for (i = 0; i < 3; i += 1) {
        for (j = 0; j < 3; j += 1) {
            if (i == 1 && j == 1)
                break 2;
            r += 1;
        }
        r += 100;
    }
}
