// test: nested for loops
// expect: r = 18
surface t_for_nested(output varying float r = 0;)
{
    float i, j;
    r = 0;
    for (i = 0; i < 3; i += 1)
        for (j = 0; j < 4; j += 1)
            r += i * j;
}
