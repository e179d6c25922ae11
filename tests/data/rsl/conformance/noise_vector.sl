// test: vector and color noise are three values in [0, 1]
// expect: r = 1
surface t_noise_vector(output varying float r = 0;)
{
    vector n = vector noise(P * 2.5);
    color c = color noise(P * 1.5);
    r = (min(xcomp(n), ycomp(n), zcomp(n)) >= 0 && max(xcomp(n), ycomp(n), zcomp(n)) <= 1 && min(comp(c, 0), comp(c, 1), comp(c, 2)) >= 0 && max(comp(c, 0), comp(c, 1), comp(c, 2)) <= 1) ? 1 : 0;
}
