// test: a macro continued over two lines with a backslash
// expect: r = 6
#define SUM3(a, b, c) \
    ((a) + (b) + (c))

surface t_pp_line_continuation(output varying float r = 0;)
{
    r = SUM3(1, 2, 3);
}
