// test: output color parameter
// expect: Ci = 0.25, 0.5, 0.75
void make(output color c)
{
    c = color(0.25, 0.5, 0.75);
}

surface t_func_array_out_color()
{
    color c;
    make(c);
    Ci = c;
}
