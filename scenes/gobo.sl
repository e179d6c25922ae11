/*
 * gobo — a spotlight with a slide in front of it: a checkerboard projected from the light.
 * The light sits at the origin of its shader space and shines along +z; the slide's pattern
 * is worked out on the plane z = 1 of that space, so the transform current at the
 * LightSource request places and aims the light and its pattern together.
 */
light gobo(
    float intensity = 1;
    color lightcolor = 1;
    color darkcolor = 0.05;
    float coneangle = radians(30);
    float frequency = 4;
    point from = point "shader" (0, 0, 0);
    vector axis = vector "shader" (0, 0, 1);)
{
    illuminate(from, axis, coneangle) {
        point Pl = transform("shader", Ps);
        float z = max(zcomp(Pl), 1e-6);
        float cx = floor(frequency * xcomp(Pl) / z);
        float cy = floor(frequency * ycomp(Pl) / z);
        float check = mod(cx + cy, 2);
        Cl = intensity * mix(darkcolor, lightcolor, check) / (L . L);
    }
}
