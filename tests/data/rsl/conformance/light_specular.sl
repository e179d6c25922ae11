// test: specular(Nf, V, 0.1), Blinn form
// expect: Ci = 0.456519845, 0.452685122, 0.4825456
// tol: 0.0001
surface t_light_specular()
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Ci = specular(Nf, V, 0.1);
}
