// test: typecasts between point, vector and normal keep the components
// expect: w = 0.5, 0.5, 0
// expect: p = 1, 2, 3
surface t_cast_point_vector(output varying vector w = 0; output varying point p = 0;)
{
    w = vector P;
    p = point(normal(1, 2, 3));
}
