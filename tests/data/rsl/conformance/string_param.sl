// test: string parameter compared in a uniform if
// expect: r = 2
surface t_string_param(string mode = "two"; output varying float r = 0;)
{
    if (mode == "one")
        r = 1;
    else if (mode == "two")
        r = 2;
    else
        r = 3;
}
