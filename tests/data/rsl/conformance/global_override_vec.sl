// test: a // global: directive overrides a triple global (N)
// global: N=0,1,0
// expect: w = 0, 1, 0
surface t_global_override_vec(output varying vector w = 0;)
{
    w = N;
}
