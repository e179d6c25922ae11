// test: faceforward(N, I, Nref) flips N to face against I
// expect: w = 0, 0, -1
// expect: p = 0, 0, 1
surface t_geo_faceforward3(output varying vector w = 0; output varying point p = 0;)
{
    w = faceforward(vector(0, 0, 1), vector(0, 0, 1), vector(0, 0, 1));
    p = point faceforward(vector(0, 0, 1), vector(0, 0, -1), vector(0, 0, 1));
}
