// test: while loop
// expect: r = 32
surface t_while_loop(output varying float r = 0;)
{
    float i = 0;
    r = 1;
    while (i < 5) {
        r *= 2;
        i += 1;
    }
}
