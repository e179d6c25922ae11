// test: a computed default is replaced by a value given for the parameter
// set: w=7
// expect: Ci = 2, 7, 0.5
surface t_compat_computed_default_set(vector dir = normalize(dPdu) * 2; float w = du * 3; color c = Cs * 0.5;)
{
    Ci = color(xcomp(dir), w, comp(c, 0));
}
