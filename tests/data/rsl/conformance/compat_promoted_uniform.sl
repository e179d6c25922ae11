// test: uniform variables assigned under varying control flow are made varying (PRMan, BMRT)
// expect: Ci = 2, 5, 0
surface t_compat_promoted_uniform()
{
    uniform float a = 1;
    if (s > 0.25)
        a = 2;
    else
        a = 3;
    uniform float k = 0;
    float i;
    for (i = 0; i < s * 10; i += 1)
        k += 1;
    Ci = color(a, k, 0);
}
