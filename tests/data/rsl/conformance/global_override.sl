// test: a // global: directive overrides s and t
// global: s=0.25 t=0.75
// expect: r = 0.25
// expect: g = 0.75
// expect: Ci = 0.25, 0.75, 0
surface t_global_override(output varying float r = 0; output varying float g = 0;)
{
    r = s;
    g = t;
    Ci = color(s, t, 0);
}
