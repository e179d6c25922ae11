// test: space-qualified constructors and matrices (object: scale 2, then translate (1, 2, 3); mycs: translate (0, 0, 5))
// lights: none
// space: object = 2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1
// space: mycs = 1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1
// expect: p = 3, 4, 5
// expect: w = 2, 0, 0
// expect: n = 0, 0, 0.5
// expect: q = 1, 2, 3
// expect: r = 1, 2, 13
surface t_spaces_ctor(output varying point p = 0; output varying vector w = 0; output varying normal n = 0;
                      output varying point q = 0; output varying point r = 0;)
{
    p = point "object" (1, 1, 1);
    w = vector "object" (1, 0, 0);
    n = normal "object" (0, 0, 1);
    matrix m = matrix "object" 1;
    q = transform(m, point(0, 0, 0));
    r = transform("mycs", m, point(0, 0, 0));
}
