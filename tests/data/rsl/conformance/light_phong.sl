// test: phong(Nf, V, size)
// expect: Ci = 0.529697049, 0.525588611, 0.56111019
// tol: 0.0001
surface t_light_phong()
{
    Ci = phong(N, -normalize(I), 2);
}
