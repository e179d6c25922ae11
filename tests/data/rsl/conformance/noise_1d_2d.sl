// test: noise(float) and noise(float, float)
// expect: r = 0.637769
// expect: g = 0.75
// tol: 0.0001
surface t_noise_1d_2d(output varying float r = 0; output varying float g = 0;)
{
    r = noise(2.3);
    g = noise(s * 3, t * 7);
}
