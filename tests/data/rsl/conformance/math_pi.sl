// test: the constant PI
// expect: r = 3.14159265
// expect: Ci = 0.785398163, 0, 0
surface t_math_pi(output varying float r = 0;)
{
    r = PI;
    Ci = color(PI / 4, 0, 0);
}
