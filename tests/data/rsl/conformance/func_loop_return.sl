// test: return from inside a loop in a function
// expect: r = 4
float first_over(float lim)
{
    float i;
    for (i = 0; i < 100; i += 1) {
        if (i * i > lim)
            return i;
    }
    return -1;
}

surface t_func_loop_return(output varying float r = 0;)
{
    r = first_over(10);
}
