/*
 * defaultsurface — what RenderMan renders where no Surface was given: a headlight matte,
 * lit by the viewing direction alone.
 *   Oi = Os, Ci = Os·Cs·(Ka + Kd·|N̂·Î|)
 */
surface defaultsurface(float Kd = 0.8, Ka = 0.2;)
{
    float d = normalize(N) . normalize(I);
    Oi = Os;
    Ci = Os * Cs * (Ka + Kd * abs(d));
}
