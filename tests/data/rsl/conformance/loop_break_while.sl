// test: break out of a while loop
// expect: r = 21
surface t_loop_break_while(output varying float r = 0;)
{
    r = 0;
    while (r < 100) {
        r += 7;
        if (r > 20)
            break;
    }
}
