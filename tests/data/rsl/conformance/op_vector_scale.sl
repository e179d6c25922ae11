// test: vector * float and vector / float
// expect: w = 1.5, -3, 6
// expect: Ci = 1.5, -3, 6
surface t_op_vector_scale(output varying vector w = 0;)
{
    w = vector(1, -2, 4) * 3 / 2;
    Ci = color(xcomp(w), ycomp(w), zcomp(w));
}
