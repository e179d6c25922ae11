/*
 * paintedplastic — RenderMan Interface 3.2 standard surface: plastic whose diffuse
 * colour is multiplied by a texture map at (s, t) (when one is named).
 *   Ct = Cs·texture(texturename)
 *   Oi = Os
 *   Ci = Os·(Ct·(Ka·ambient() + Kd·diffuse(Nf)) + specularcolor·Ks·specular(Nf, V, roughness))
 */
surface paintedplastic(
    float Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1;
    color specularcolor = 1;
    string texturename = "";)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color Ct = Cs;
    if (texturename != "")
        Ct *= color texture(texturename);
    Oi = Os;
    Ci = Os * (Ct * (Ka * ambient() + Kd * diffuse(Nf))
               + specularcolor * Ks * specular(Nf, V, roughness));
}
