// test: a function defined inside the shader body
// expect: r = 8.125
surface t_func_in_shader(output varying float r = 0;)
{
    float cube(float x)
    {
        return x * x * x;
    }
    r = cube(2) + cube(s);
}
