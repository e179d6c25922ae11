// test: ! negates a relation
// expect: r = 0
// expect: g = 1
surface t_op_not(output varying float r = 0; output varying float g = 0;)
{
    r = !(1 < 2) ? 1 : 0;
    g = !(2 < 1) ? 1 : 0;
}
