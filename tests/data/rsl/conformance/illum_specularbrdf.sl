// test: specularbrdf(normalize(L), N, V, roughness) inside illuminance equals specular()
// expect: Ci = 0.723957116, 0.720823223, 0.775736898
// expect: c = 0, 0, 0
// tol: 0.0001
surface t_illum_specularbrdf(output varying color c = 0;)
{
    vector V = -normalize(I);
    Ci = 0;
    illuminance(P, N, PI / 2) {
        Ci += Cl * specularbrdf(normalize(L), N, V, 0.2);
    }
    c = Ci - specular(N, V, 0.2);
}
