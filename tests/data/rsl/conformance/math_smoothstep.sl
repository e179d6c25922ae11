// test: smoothstep inside and outside the ramp
// expect: r = 0.15625
// expect: g = 10
surface t_math_smoothstep(output varying float r = 0; output varying float g = 0;)
{
    r = smoothstep(0, 1, 0.25);
    g = smoothstep(0.2, 0.4, 0.1) + 10 * smoothstep(0.2, 0.4, 0.5);
}
