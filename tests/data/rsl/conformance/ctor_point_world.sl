// test: point "world" (x, y, z) parses (identity in the harness)
// expect: p = 0.5, -1, 2
surface t_ctor_point_world(output varying point p = 0;)
{
    p = point "world" (0.5, -1, 2);
}
