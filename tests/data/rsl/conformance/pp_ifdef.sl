// test: #ifdef / #else / #endif and #if with an expression
// expect: r = 2
// expect: g = 3
#define SIZE 3

surface t_pp_ifdef(output varying float r = 0; output varying float g = 0;)
{
#ifdef FANCY
    r = 1;
#else
    r = 2;
#endif
#if SIZE > 2
    g = 3;
#else
    g = 4;
#endif
}
