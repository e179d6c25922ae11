// test: length of a vector
// expect: r = 13
surface t_geo_length(output varying float r = 0;)
{
    r = length(vector(3, 4, 12));
}
