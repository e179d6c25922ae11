// test: else if chain
// expect: r = 3
surface t_if_else_chain(output varying float r = 0;)
{
    float x = 0.6;
    if (x < 0.2)
        r = 1;
    else if (x < 0.4)
        r = 2;
    else if (x < 0.8)
        r = 3;
    else
        r = 4;
}
