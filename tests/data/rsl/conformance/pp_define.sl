// test: #define of an object-like macro
// expect: r = 1.5
#define HALF 0.5

surface t_pp_define(output varying float r = 0;)
{
    r = HALF * 3;
}
