// test: break leaves the innermost loop
// expect: r = 4
surface t_loop_break(output varying float r = 0;)
{
    float i;
    r = 0;
    for (i = 0; i < 10; i += 1) {
        if (i == 4)
            break;
        r += 1;
    }
}
