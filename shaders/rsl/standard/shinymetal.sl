/*
 * shinymetal — RenderMan Interface 3.2 standard surface: metal plus a mirror
 * reflection looked up in an environment map (when one is named).
 *   D   = reflect(I, Nf), taken to "world" space for the lookup
 *   Oi  = Os
 *   Ci  = Os·Cs·(Ka·ambient() + Ks·specular(Nf, V, roughness) + Kr·environment(texturename, D))
 */
surface shinymetal(
    float Ka = 1, Ks = 1, Kr = 1, roughness = 0.1;
    string texturename = "";)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color env = 0;
    if (texturename != "") {
        vector D = reflect(I, normalize(Nf));
        D = vtransform("world", D);
        env = Kr * color environment(texturename, D);
    }
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness) + env);
}
