// test: specular with roughness 0.5
// expect: Ci = 0.955461396, 0.953777347, 1.03254099
// tol: 0.0001
surface t_light_specular_rough()
{
    Ci = specular(N, -normalize(I), 0.5);
}
