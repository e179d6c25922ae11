// test: a // set: directive overrides a color parameter
// set: tint=0.25,0.5,0.75
// expect: Ci = 0.25, 0.5, 0.75
surface t_param_set_color(color tint = color(1, 0, 0);)
{
    Ci = tint;
}
