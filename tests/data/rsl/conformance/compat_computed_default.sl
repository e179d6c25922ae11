// test: parameter defaults that are not constants are computed when the shader runs (PRMan, BMRT)
// expect: Ci = 2, 3, 0.5
surface t_compat_computed_default(vector dir = normalize(dPdu) * 2; float w = du * 3; color c = Cs * 0.5;)
{
    Ci = color(xcomp(dir), w, comp(c, 0));
}
