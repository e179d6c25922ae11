/*
 * spotlight — a point light restricted to a cone with a soft edge (RenderMan
 * Interface 3.2 standard light). Port of shaders/src/lights/spotlight.rs: with
 * A = normalize(to - from) and cosangle = L·A/|L|,
 *   illuminate(from, A, coneangle) {
 *       Cl = intensity·lightcolor·max(cosangle, 0)^beamdistribution / (L·L)
 *            · smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle) }
 * Angles are in radians (the defaults are radians(30) and radians(5)); at the light
 * itself (L = 0) cosangle is taken as 1. from and to are in "current" space.
 */
light spotlight(
    uniform float intensity = 1;
    uniform color lightcolor = 1;
    uniform point from = point (0, 0, 0);
    uniform point to = point (0, 0, 1);
    uniform float coneangle = 0.5235987755982988;       /* radians(30) */
    uniform float conedeltaangle = 0.08726646259971648; /* radians(5) */
    uniform float beamdistribution = 2;)
{
    uniform vector A = normalize(to - from);
    uniform float cosoutside = cos(coneangle);
    uniform float cosinside = cos(coneangle - conedeltaangle);
    illuminate(from, A, coneangle) {
        float len2 = L . L;
        float safe_len2 = (len2 <= 0) ? 1 : len2;
        float cosangle = (len2 <= 0) ? 1 : (L . A) / sqrt(safe_len2);
        float beam = pow(max(cosangle, 0), beamdistribution);
        float atten = beam / len2 * smoothstep(cosoutside, cosinside, cosangle);
        Cl = lightcolor * (intensity * atten);
    }
}
