// test: && truth table
// expect: r = 1
// expect: Ci = 1, 1, 1
surface t_op_and(output varying float r = 0;)
{
    r = 0;
    if (1 < 2 && 2 < 3) r += 1;
    if (1 < 2 && 3 < 2) r += 10;
    if (2 < 1 && 2 < 3) r += 100;
    Ci = r;
}
