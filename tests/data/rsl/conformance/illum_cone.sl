// test: a narrow cone (0.85 rad) around N admits only light 1
// expect: r = 1
// expect: c = 0.9, 0.85, 0.8
surface t_illum_cone(output varying float r = 0; output varying color c = 0;)
{
    r = 0;
    illuminance(P, N, 0.85) {
        r += 1;
        c += Cl;
    }
}
