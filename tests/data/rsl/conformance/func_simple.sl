// test: a user function returning a float
// expect: r = 9.25
float sq(float x)
{
    return x * x;
}

surface t_func_simple(output varying float r = 0;)
{
    r = sq(3) + sq(s);
}
