// test: pnoise value equals noise inside the first period
// expect: r = 0
// tol: 0.0001
surface t_pnoise_value(output varying float r = 0;)
{
    r = pnoise(point(0.3, 0.7, 1.2), point(8, 8, 8)) - noise(point(0.3, 0.7, 1.2));
}
