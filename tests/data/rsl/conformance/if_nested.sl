// test: nested if with blocks (dangling else binds to the inner if)
// expect: r = 2
surface t_if_nested(output varying float r = 0;)
{
    r = 0;
    if (s > 0.25) {
        if (t > 0.75)
            r = 1;
        else
            r = 2;
    }
    if (s > 0.75)
        if (t > 0)
            r += 10;
        else
            r += 100;
}
