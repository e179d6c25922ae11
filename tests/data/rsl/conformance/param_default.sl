// test: a shader parameter keeps its default
// expect: r = 0.75
// expect: Ci = 0.75, 0.75, 0.75
surface t_param_default(float Kd = 0.75; output varying float r = 0;)
{
    r = Kd;
    Ci = Kd;
}
