// test: return from inside an if, before the end of the function
// expect: r = 1
// expect: g = 0.25
float clamp01(float x)
{
    if (x > 1)
        return 1;
    return x;
}

surface t_func_early_return(output varying float r = 0; output varying float g = 0;)
{
    r = clamp01(1.5);
    g = clamp01(0.25);
}
