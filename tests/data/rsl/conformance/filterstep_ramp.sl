// test: filterstep inside the ramp: clamp((x - edge)/width + 0.5, 0, 1)
// expect: r = 0.4
// expect: g = 0.6
surface t_filterstep_ramp(output varying float r = 0; output varying float g = 0;)
{
    r = filterstep(0.3, s * 0.5);
    g = filterstep(0.2, s * 0.25 + t * 0.25);
}
