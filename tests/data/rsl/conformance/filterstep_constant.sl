// test: filterstep of a constant (zero width) is step
// expect: r = 1
// expect: g = 0
surface t_filterstep_constant(output varying float r = 0; output varying float g = 0;)
{
    r = filterstep(0.5, 0.75);
    g = filterstep(0.5, 0.25);
}
