// test: fresnel(I, N, eta, Kr, Kt): Kr + Kt = 1 and the Fresnel formula
// expect: r = 0.040048786
// expect: g = 1
surface t_geo_fresnel_k(output varying float r = 0; output varying float g = 0;)
{
    float kr, kt;
    fresnel(I, N, 1 / 1.5, kr, kt);
    r = kr;
    g = kr + kt;
}
