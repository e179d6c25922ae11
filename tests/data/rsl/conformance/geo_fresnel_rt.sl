// test: fresnel with the R and T outputs (R = reflect, T = refract of normalize(I))
// expect: w = 0.162221421, 0.162221421, 0.973328527
// expect: p = 0.108147614, 0.108147614, -0.988234885
surface t_geo_fresnel_rt(output varying vector w = 0; output varying point p = 0;)
{
    float kr, kt;
    vector R, T;
    fresnel(I, N, 1 / 1.5, kr, kt, R, T);
    w = R;
    p = point T;
}
