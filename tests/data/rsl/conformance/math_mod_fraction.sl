// test: mod by a fractional divisor
// expect: r = 0.1
surface t_math_mod_fraction(output varying float r = 0;)
{
    r = mod(1, 0.3);
}
