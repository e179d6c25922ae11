// test: diffuse with no lights is 0
// lights: none
// expect: Ci = 0.25, 0.25, 0.25
surface t_light_diffuse_none()
{
    Ci = diffuse(N) + 0.25;
}
