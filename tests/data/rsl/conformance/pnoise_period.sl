// test: pnoise repeats with its period
// expect: r = 0
// expect: g = 0
surface t_pnoise_period(output varying float r = 0; output varying float g = 0;)
{
    point q = point(0.3, 1.6, 2.2);
    r = pnoise(q, point(4, 4, 4)) - pnoise(q + vector(4, -8, 12), point(4, 4, 4));
    g = pnoise(1.3, 3) - pnoise(7.3, 3);
}
