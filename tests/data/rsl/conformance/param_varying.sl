// test: a varying parameter with a default
// expect: r = 0.25
surface t_param_varying(varying float k = 0.5; output varying float r = 0;)
{
    r = k * s;
}
