// test: transform/vtransform/ntransform to spaces the context names (object: scale 2, then translate (1, 2, 3); mycs: translate (0, 0, 5))
// lights: none
// space: object = 2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1
// space: mycs = 1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1
// expect: p = -0.25, -0.75, -1.5
// expect: w = 0.25, 0.25, -1.5
// expect: n = 0, 0, 2
// expect: q = 0.5, 0.5, -5
surface t_spaces_transform(output varying point p = 0; output varying vector w = 0; output varying normal n = 0;
                           output varying point q = 0;)
{
    p = transform("object", P);
    w = vtransform("object", I);
    n = ntransform("object", N);
    q = transform("mycs", P);
}
