// test: Cs and Os default to white; Ci = Os * Cs
// expect: Ci = 1, 1, 1
// expect: Oi = 0.5, 0.5, 0.5
surface t_global_Cs_Os()
{
    Oi = Os * 0.5;
    Ci = Os * Cs;
}
