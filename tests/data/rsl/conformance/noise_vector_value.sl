// test: vector noise(point) value (three seeds)
// expect: w = 0.431620722, 0.370842594, 0.472339267
// tol: 0.0001
surface t_noise_vector_value(output varying vector w = 0;)
{
    w = vector noise(point(0.3, 0.7, 1.2));
}
