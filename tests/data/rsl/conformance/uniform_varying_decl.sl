// test: uniform and varying locals mix in expressions
// expect: r = 3
surface t_uniform_varying_decl(output varying float r = 0;)
{
    uniform float k = 2;
    varying float x = s * k;
    r = x + k;
}
