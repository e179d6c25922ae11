// test: asin and acos
// expect: r = 0.304692654
// expect: g = 2.21429744
surface t_math_asin_acos(output varying float r = 0; output varying float g = 0;)
{
    r = asin(0.3);
    g = acos(-0.6);
}
