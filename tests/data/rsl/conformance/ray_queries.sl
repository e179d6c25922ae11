// test: outside a scene the ray queries answer a camera ray with nothing in the way
// expect: level = 0
// expect: shadowray = 0
// expect: indirect = 0
// expect: occl = 0
// expect: found = 0
// expect: ind = 0, 0, 0
// expect: caus = 0, 0, 0
// expect: trans = 1, 1, 1
surface t_ray_queries(output varying float level = 7; output varying float shadowray = 7;
    output varying float indirect = 7; output varying float occl = 7; output varying float found = 7;
    output varying color ind = 7; output varying color caus = 7; output varying color trans = 7;)
{
    float d = 3;
    level = raylevel();
    shadowray = isshadowray();
    indirect = isindirectray();
    occl = occlusion(P, N, 16);
    found = rayinfo("depth", d);
    ind = indirectdiffuse(P, N, 16);
    caus = caustic(P, N);
    trans = transmission(P, P + N);
}
