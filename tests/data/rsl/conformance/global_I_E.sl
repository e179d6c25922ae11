// test: I = P - E with E = (0, 0, 3)
// expect: w = 0.5, 0.5, -3
// expect: p = 0, 0, 3
surface t_global_I_E(output varying vector w = 0; output varying point p = 0;)
{
    w = I;
    p = E;
}
