// test: noise at integer lattice points is 0.5, snoise is 0
// expect: r = 1
// expect: g = 0
surface t_noise_lattice(output varying float r = 0; output varying float g = 0;)
{
    r = noise(point(1, 2, 3)) + noise(point(-4, 0, 7));
    g = snoise(point(2, -3, 5));
}
