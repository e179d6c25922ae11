// test: transform/vtransform from one named space to another (object: scale 2, then translate (1, 2, 3); shader: 90 degrees about z)
// lights: none
// space: object = 2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1
// space: shader = 0,1,0,0, -1,0,0,0, 0,0,1,0, 0,0,0,1
// expect: p = 3, -2, 3
// expect: w = 0, -2, 0
// expect: c = 0, 1, 0
surface t_spaces_between(output varying point p = 0; output varying vector w = 0; output varying point c = 0;)
{
    p = transform("object", "shader", P);
    w = vtransform("object", "shader", vector(1, 0, 0));
    c = transform("shader", "current", point(1, 0, 0));
}
