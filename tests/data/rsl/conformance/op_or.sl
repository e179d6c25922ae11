// test: || truth table
// expect: r = 11
// expect: Ci = 11, 11, 11
surface t_op_or(output varying float r = 0;)
{
    r = 0;
    if (1 < 2 || 3 < 2) r += 1;
    if (2 < 1 || 2 < 3) r += 10;
    if (2 < 1 || 3 < 2) r += 100;
    Ci = r;
}
