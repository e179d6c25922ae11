/*
 * bumpy — RenderMan Interface 3.2 standard displacement shader: moves P along the
 * normal by Km times a (float) texture map at (s, t), then recomputes N.
 *   P += Km·texture(texturename, s, t)·normalize(N), N = calculatenormal(P)
 */
displacement bumpy(float Km = 1; string texturename = "";)
{
    if (texturename != "") {
        float amp = Km * float texture(texturename, s, t);
        P += amp * normalize(N);
        N = calculatenormal(P);
    }
}
