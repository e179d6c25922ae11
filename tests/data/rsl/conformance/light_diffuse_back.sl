// test: diffuse of the back-facing normal sees no light
// expect: Ci = 0, 0, 0
surface t_light_diffuse_back()
{
    Ci = diffuse(-N);
}
