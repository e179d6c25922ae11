// test: a void function with no return statement
// expect: r = 3
void bump(output float x)
{
    x += 1;
}

surface t_func_void_no_return(output varying float r = 0;)
{
    r = 0;
    bump(r);
    bump(r);
    bump(r);
}
