/*
 * vignette — darkens towards the corners of a `width` × `height` raster and paints the
 * uncovered part of each pixel with `bg`; reads `P`, `Ci`, `Oi`, `alpha`, writes all three.
 */
imager vignette(float width = 64, height = 48, strength = 0.6; color bg = color (0.2, 0.3, 0.4);)
{
    float x = 2 * xcomp(P) / width - 1, y = 2 * ycomp(P) / height - 1;
    float k = 1 - strength * (x * x + y * y) / 2;
    Ci = k * Ci + (1 - alpha) * bg;
    Oi = max(Oi, alpha);
    alpha = 1 - 0.5 * (1 - alpha);
}
