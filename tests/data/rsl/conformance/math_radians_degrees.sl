// test: radians and degrees
// expect: r = 1.57079633
// expect: g = 57.2957795
// tol: 0.0001
surface t_math_radians_degrees(output varying float r = 0; output varying float g = 0;)
{
    r = radians(90);
    g = degrees(1);
}
