/*
 * background — RenderMan Interface 3.2 standard imager shader (Appendix A.6): the
 * background colour shows through where the pixel is not covered (alpha < 1); the pixel
 * becomes opaque.
 */
imager background(color background = 1;)
{
    Ci += (1 - alpha) * background;
    Oi = 1;
    alpha = 1;
}
