// test: user function with point and vector parameters returning a vector
// expect: w = 1, 0, -2
vector halfway(point a, b)
{
    return (b - a) * 0.5;
}

surface t_func_point_vector(output varying vector w = 0;)
{
    w = halfway(point(1, 2, 3), point(3, 2, -1));
}
