// test: rotate(Q, angle, P0, P1) about an axis through two points
// expect: p = 1, 2, 0
surface t_geo_rotate(output varying point p = 0;)
{
    p = rotate(point(2, 1, 0), PI / 2, point(1, 1, 0), point(1, 1, 1));
}
