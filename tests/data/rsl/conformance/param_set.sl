// test: a // set: directive overrides a float parameter
// set: Kd=0.5
// expect: r = 0.5
// expect: Ci = 1, 1, 1
surface t_param_set(float Kd = 1; output varying float r = 0;)
{
    r = Kd;
    Ci = Kd * 2;
}
