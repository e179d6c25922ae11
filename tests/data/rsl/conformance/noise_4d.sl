// test: noise(point, float) is in [0, 1] and 0.5 on the 4D lattice
// expect: r = 1
// expect: g = 0.5
surface t_noise_4d(output varying float r = 0; output varying float g = 0;)
{
    float n = noise(point(0.3, 1.7, 2.2), 0.6);
    r = (n >= 0 && n <= 1) ? 1 : 0;
    g = noise(point(1, 2, 3), 4);
}
