// test: distance between two points
// expect: r = 5
surface t_geo_distance(output varying float r = 0;)
{
    r = distance(point(1, 2, 3), point(4, 6, 3));
}
