// test: #define of a function-like macro with two arguments
// expect: r = 3
#define LERP(a, b, x) ((a) + ((b) - (a)) * (x))

surface t_pp_macro_args(output varying float r = 0;)
{
    r = LERP(2, 6, 0.25);
}
