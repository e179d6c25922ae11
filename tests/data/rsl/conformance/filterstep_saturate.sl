// test: filterstep far from its edge is 0 or 1
// expect: r = 0
// expect: g = 1
surface t_filterstep_saturate(output varying float r = 0; output varying float g = 0;)
{
    r = filterstep(2, s);
    g = filterstep(-2, t);
}
