// test: array of strings
// expect: r = 1
surface t_array_string(output varying float r = 0;)
{
    string names[2] = {"alpha", "beta"};
    r = (names[1] == "beta") ? 1 : 0;
}
