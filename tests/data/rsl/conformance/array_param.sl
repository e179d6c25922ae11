// test: array shader parameter with a default initializer
// expect: r = 0.875
// expect: Ci = 0.5, 0.25, 0.125
surface t_array_param(float k[3] = {0.5, 0.25, 0.125}; output varying float r = 0;)
{
    r = k[0] + k[1] + k[2];
    Ci = color(k[0], k[1], k[2]);
}
