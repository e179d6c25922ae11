// test: Cl inside illuminance is the light colour (no falloff in table1)
// expect: Ci = 1.15, 1.15, 1.25
surface t_illum_Cl()
{
    Ci = 0;
    illuminance(P, N, PI) {
        Ci += Cl;
    }
}
