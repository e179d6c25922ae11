// test: a user function reads the globals s and P
// expect: r = 1
float f()
{
    return s + xcomp(P);
}

surface t_func_globals(output varying float r = 0;)
{
    r = f();
}
