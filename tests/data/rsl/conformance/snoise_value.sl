// test: snoise(point) value and range
// expect: r = -0.0928001404
// expect: g = 1
// tol: 0.0001
surface t_snoise_value(output varying float r = 0; output varying float g = 0;)
{
    r = snoise(point(1.25, -0.5, 2.75));
    g = (abs(snoise(P * 5.3)) <= 1) ? 1 : 0;
}
