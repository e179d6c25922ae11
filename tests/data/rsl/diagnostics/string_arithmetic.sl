// error: a string used in arithmetic
// at: 6:9
surface d_string_arithmetic(output varying float r = 0;)
{
    string name = "abc";
    r = name * 2;
}
