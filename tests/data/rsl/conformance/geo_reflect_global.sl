// test: reflect of the global I about N
// expect: w = 0.5, 0.5, 3
surface t_geo_reflect_global(output varying vector w = 0;)
{
    w = reflect(I, N);
}
