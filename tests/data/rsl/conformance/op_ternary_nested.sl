// test: nested ?: in the false branch
// expect: r = 3
// expect: Ci = 3, 3, 3
surface t_op_ternary_nested(output varying float r = 0;)
{
    float x = 0.6;
    r = (x < 0.25) ? 1 : (x < 0.5) ? 2 : (x < 0.75) ? 3 : 4;
    Ci = r;
}
