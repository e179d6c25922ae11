// test: concat joins strings
// expect: r = 1
surface t_string_concat(output varying float r = 0;)
{
    string a = concat("ab", "cd", "e");
    r = (a == "abcde") ? 1 : 0;
}
