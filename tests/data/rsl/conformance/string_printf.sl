// test: printf compiles and does not change results
// expect: r = 1
surface t_string_printf(output varying float r = 0;)
{
    printf("s = %f, P = %p, Cs = %c\n", s, P, Cs);
    r = 1;
}
