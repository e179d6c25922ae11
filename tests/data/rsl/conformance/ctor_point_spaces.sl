// test: point constructors in "current", "object" and "camera" spaces (identity in the harness)
// expect: p = 1, 1, 1
surface t_ctor_point_spaces(output varying point p = 0;)
{
    p = point "current" (1, 0, 0) + vector "object" (0, 1, 0) + vector "camera" (0, 0, 1);
}
