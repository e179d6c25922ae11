// test: noise(p) is in [0, 1] at several points
// expect: r = 1
surface t_noise_range(output varying float r = 0;)
{
    r = 1;
    float i;
    for (i = 0; i < 20; i += 1) {
        float n = noise(point(i * 0.37, i * 1.13 + 0.2, 3 - i * 0.71));
        if (n < 0 || n > 1)
            r = 0;
    }
}
