// test: output parameters of a user function
// expect: r = 3
// expect: g = 0.75
void split(float x; output float ip, fp)
{
    ip = floor(x);
    fp = x - ip;
}

surface t_func_output_param(output varying float r = 0; output varying float g = 0;)
{
    float a, b;
    split(3.75, a, b);
    r = a;
    g = b;
}
