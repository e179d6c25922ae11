// test: fresnel Kr at 45 degrees into water
// expect: r = 0.0275213836
surface t_geo_fresnel_45(output varying float r = 0;)
{
    float kr, kt;
    fresnel(vector(1, 0, -1), normal(0, 0, 1), 1 / 1.33, kr, kt);
    r = kr;
}
