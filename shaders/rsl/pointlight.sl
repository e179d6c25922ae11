/*
 * pointlight — light from a point (RenderMan Interface 3.2 standard light), with the
 * distance law generalised to 1/|L|^falloff. Port of shaders/src/lights/pointlight.rs:
 *   illuminate(from) { Cl = intensity·lightcolor / (L·L)^(falloff/2) }
 * falloff 2 (the default) is the classic inverse square, 0 a light without falloff.
 * `from` is in "current" space, as the Rust takes it (no "shader" space transform).
 */
light pointlight(
    uniform float intensity = 1;
    uniform color lightcolor = 1;
    uniform point from = point (0, 0, 0);
    uniform float falloff = 2;)
{
    illuminate(from) {
        /* falloff is uniform: a branch on a parameter, not on a point. */
        if (falloff == 0)
            Cl = lightcolor * intensity;
        else if (falloff == 2)
            Cl = lightcolor * intensity / (L . L);
        else
            Cl = lightcolor * intensity / pow(L . L, falloff * 0.5);
    }
}
