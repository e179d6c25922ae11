// test: diffuse(Nf) over the table1 lights
// expect: Ci = 0.788857728, 0.783175391, 0.837195285
// tol: 0.0001
surface t_light_diffuse()
{
    normal Nf = faceforward(normalize(N), I);
    Ci = diffuse(Nf);
}
