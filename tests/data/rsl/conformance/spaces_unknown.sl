// test: a space the context does not know is the identity (with a warning at run time)
// lights: none
// space: mycs = 1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1
// expect: p = 0.5, 0.5, 0
// expect: w = 0, 0, 1
surface t_spaces_unknown(output varying point p = 0; output varying vector w = 0;)
{
    p = transform("no such space", P);
    w = vtransform("no such space", "raster", vector(0, 0, 1));
}
