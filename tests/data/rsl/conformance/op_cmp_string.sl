// test: == and != on strings
// expect: r = 1
// expect: g = 0
surface t_op_cmp_string(output varying float r = 0; output varying float g = 0;)
{
    string a = "plastic";
    r = (a == "plastic") ? 1 : 0;
    g = (a != "plastic") ? 1 : 0;
}
