// test: transform/vtransform/ntransform between named spaces (identity in the harness)
// expect: p = 2, 3, 4
// expect: w = 0, 1, 2
surface t_transform_spaces(output varying point p = 0; output varying vector w = 0;)
{
    p = transform("world", point(1, 2, 3)) + vtransform("shader", "object", vector(1, 1, 1));
    w = vtransform("camera", vector(0, 1, 0)) + ntransform("object", "world", normal(0, 0, 2));
}
