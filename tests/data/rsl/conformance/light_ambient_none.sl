// test: ambient() with no lights is 0
// lights: none
// expect: Ci = 0.5, 0, 0
surface t_light_ambient_none()
{
    Ci = ambient() + color(0.5, 0, 0);
}
