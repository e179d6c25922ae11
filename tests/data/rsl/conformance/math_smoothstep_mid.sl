// test: smoothstep at the midpoint is 0.5; with a varying x
// expect: r = 0.5
surface t_math_smoothstep_mid(output varying float r = 0;)
{
    r = smoothstep(0.25, 0.75, s);
}
