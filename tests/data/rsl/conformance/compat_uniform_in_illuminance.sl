// test: uniform statements in an illuminance loop run once per light (PRMan; Advanced RenderMan's lensflare)
// expect: Ci = 2, 2, 0
surface t_compat_uniform_in_illuminance()
{
    uniform float n = 0;
    float lit = 0;
    illuminance (P) {
        n += 1;
        lit += 1;
    }
    Ci = color(n, lit, 0);
}
