// test: noise(point) value (gradient noise of the shading workload, section 4)
// expect: r = 0.431620722
// expect: g = 0.336160185
// tol: 0.0001
surface t_noise_value(output varying float r = 0; output varying float g = 0;)
{
    r = noise(point(0.3, 0.7, 1.2));
    g = noise(P * 3.7);
}
