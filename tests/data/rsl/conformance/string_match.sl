// test: match(pattern, subject) is a regular-expression search
// expect: r = 1
// expect: g = 0
surface t_string_match(output varying float r = 0; output varying float g = 0;)
{
    r = match("b.d", "abcde");
    g = match("^x", "abc");
}
