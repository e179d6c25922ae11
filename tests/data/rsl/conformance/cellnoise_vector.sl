// test: vector cellnoise: three values in [0, 1)
// expect: w = 0.440733969, 0.361462831, 0.600410581
surface t_cellnoise_vector(output varying vector w = 0;)
{
    w = vector cellnoise(point(0.5, 1.5, 2.5));
}
