/*
 * distantlight — parallel light along a direction (RenderMan Interface 3.2 standard
 * light). Port of shaders/src/lights/distantlight.rs:
 *   solar(to - from, 0) { Cl = intensity·lightcolor }
 * from and to are in "current" space, as the Rust takes them.
 */
light distantlight(
    uniform float intensity = 1;
    uniform color lightcolor = 1;
    uniform point from = point (0, 0, 0);
    uniform point to = point (0, 0, 1);)
{
    solar(to - from, 0) {
        Cl = lightcolor * intensity;
    }
}
