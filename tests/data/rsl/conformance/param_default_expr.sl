// test: a parameter default may be an expression using another constant
// expect: r = 13
surface t_param_default_expr(float a = 2; float b = 3 * 4 - 1; output varying float r = 0;)
{
    r = a + b;
}
