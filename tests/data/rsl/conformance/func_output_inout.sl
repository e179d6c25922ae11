// test: an output parameter is read and written (pass by reference)
// expect: r = 8
void twice(output float x)
{
    x *= 2;
}

surface t_func_output_inout(output varying float r = 0;)
{
    r = 2;
    twice(r);
    twice(r);
}
