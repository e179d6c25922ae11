/*
 * ambientlight — constant light without direction, seen only by ambient()
 * (RenderMan Interface 3.2 standard light). Port of shaders/src/lights/ambientlight.rs:
 *   Cl = intensity·lightcolor, L = 0
 */
light ambientlight(
    uniform float intensity = 1;
    uniform color lightcolor = 1;)
{
    Cl = lightcolor * intensity;
    L = 0;
}
