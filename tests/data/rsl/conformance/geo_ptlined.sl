// test: ptlined: distance from a point to a segment, inside and beyond an end
// expect: r = 1
// expect: g = 4.12310563
surface t_geo_ptlined(output varying float r = 0; output varying float g = 0;)
{
    r = ptlined(point(0, 0, 0), point(2, 0, 0), point(1, 1, 0));
    g = ptlined(point(0, 0, 0), point(2, 0, 0), point(3, 0, 4));
}
