// test: format with %s and %.2f
// expect: r = 1
// expect: g = 1
surface t_string_format(output varying float r = 0; output varying float g = 0;)
{
    string a = format("%s-%s", "x", "y");
    r = (a == "x-y") ? 1 : 0;
    g = (format("%.2f", 0.5) == "0.50") ? 1 : 0;
}
