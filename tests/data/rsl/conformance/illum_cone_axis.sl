// test: a cone around another axis: only light 2 is within 0.5 rad of (1, -0.6, 0.8)
// expect: r = 10
surface t_illum_cone_axis(output varying float r = 0;)
{
    r = 0;
    illuminance(P, vector(1, -0.6, 0.8), 0.5) {
        r += 10;
    }
}
