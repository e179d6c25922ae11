// test: the plastic model: Cs*(Ka*ambient() + Kd*diffuse(Nf)) + Ks*specular(Nf, V, roughness)
// expect: Ci = 0.702688787, 0.697930256, 0.759870443
// expect: Oi = 1, 1, 1
// tol: 0.0001
surface t_light_plastic(float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, V, roughness));
}
