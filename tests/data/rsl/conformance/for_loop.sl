// test: for loop summing 1..10
// expect: r = 55
surface t_for_loop(output varying float r = 0;)
{
    float i;
    r = 0;
    for (i = 1; i <= 10; i += 1)
        r += i;
}
