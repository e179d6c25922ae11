// test: L inside illuminance points from the surface to the light (unnormalized)
// expect: w = 0, 1.5, 8
surface t_illum_L(output varying vector w = 0;)
{
    illuminance(P) {
        w += L;
    }
}
