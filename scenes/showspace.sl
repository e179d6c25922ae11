/*
 * showspace: colours a surface by the position of P in a named coordinate system, scaled and
 * offset (Ci = transform(space, P) * scale + offset), opaque. For scenes/spaces.rib and the
 * known-answer tests of named spaces.
 */
surface showspace(string space = "object"; float scale = 1; float offset = 0;)
{
    Ci = color(transform(space, P)) * scale + offset;
    Oi = 1;
}
