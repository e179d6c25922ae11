// test: u = v = s = t = 0.5 on a 1x1 grid
// expect: Ci = 1, 0.5, 0.5
surface t_global_uv_st()
{
    Ci = color(u + v, s, t);
}
