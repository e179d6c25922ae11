// test: a hand-written diffuse loop equals diffuse()
// expect: Ci = 0.788857728, 0.783175391, 0.837195285
// expect: c = 0, 0, 0
// tol: 0.0001
surface t_illum_custom_diffuse(output varying color c = 0;)
{
    normal Nf = faceforward(normalize(N), I);
    Ci = 0;
    illuminance(P, Nf, PI / 2) {
        Ci += Cl * (normalize(L) . Nf);
    }
    c = Ci - diffuse(Nf);
}
