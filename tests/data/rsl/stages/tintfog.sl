/*
 * tintfog — exponential fog whose result is scaled by `tint`, so that a `Ci` that does not
 * start as what arrives shows; and `Oi` rises only where `length(I)` passes `onset`.
 */
volume tintfog(float distance = 2; color background = color (0.1, 0.2, 0.7); float tint = 0.8;
               float onset = 0.5;)
{
    float d = 1 - exp(-length(I) / distance);
    Ci = tint * mix(Ci, background, d);
    if (length(I) > onset)
        Oi = mix(Oi, color (1, 1, 1), d);
}
