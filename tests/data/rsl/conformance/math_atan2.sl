// test: atan(y, x) covers all quadrants
// expect: r = 2.35619449
// expect: g = -2.03444394
surface t_math_atan2(output varying float r = 0; output varying float g = 0;)
{
    r = atan(1, -1);
    g = atan(-2, -1);
}
