// test: a function defined inside another function
// expect: r = 7
float outer(float x)
{
    float inner(float y)
    {
        return y * 3;
    }
    return inner(x) + 1;
}

surface t_func_nested(output varying float r = 0;)
{
    r = outer(2);
}
