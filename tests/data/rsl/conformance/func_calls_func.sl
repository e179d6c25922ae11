// test: a function calls another user function
// expect: r = 4
float a(float x)
{
    return x + 1;
}

float b(float x)
{
    return a(x) * 2;
}

surface t_func_calls_func(output varying float r = 0;)
{
    r = b(1);
}
