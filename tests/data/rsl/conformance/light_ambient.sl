// test: ambient() sums the ambient lights
// expect: Ci = 0.08, 0.08, 0.1
surface t_light_ambient()
{
    Ci = ambient();
}
