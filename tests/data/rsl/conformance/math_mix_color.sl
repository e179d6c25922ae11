// test: mix on colors with a float weight
// expect: Ci = 0.75, 0, 0.25
surface t_math_mix_color()
{
    Ci = mix(color(1, 0, 0), color(0, 0, 1), 0.25);
}
