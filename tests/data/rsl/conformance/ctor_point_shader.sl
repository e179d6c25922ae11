// test: point "shader" (x, y, z) parses (all spaces are the identity in the harness)
// expect: p = 1, 2, 3
surface t_ctor_point_shader(output varying point p = 0;)
{
    p = point "shader" (1, 2, 3);
}
