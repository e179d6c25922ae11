// test: several declarators in one declaration, with and without initializers
// expect: r = 341
surface t_decl_multi(output varying float r = 0;)
{
    float a = 1, b, c = 3;
    b = a + c;
    r = a + b * 10 + c * 100;
}
