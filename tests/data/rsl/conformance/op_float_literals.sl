// test: float literal forms: integer, leading dot, exponent
// expect: r = 2.6
// expect: g = 2.5
// expect: Ci = 2.6, 2.5, 0
surface t_op_float_literals(output varying float r = 0; output varying float g = 0;)
{
    r = .5 + 2. + 1e-1;
    g = 2.5E2 * 1e-2;
    Ci = color(r, g, 0);
}
