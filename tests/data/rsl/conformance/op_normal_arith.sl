// test: normal arithmetic: normal + normal, normal * float
// expect: w = 1, 2, 2
surface t_op_normal_arith(output varying vector w = 0;)
{
    normal n1 = normal(0, 0, 1);
    normal n2 = normal(1, 2, 0);
    w = n1 * 2 + n2;
}
