// test: vector "world" and normal "object" constructors
// expect: w = 1, 2, 4
surface t_ctor_normal_vector_space(output varying vector w = 0;)
{
    w = vector "world" (1, 2, 3) + normal "object" (0, 0, 1);
}
