/*
 * fog — RenderMan Interface 3.2 standard volume shader (Appendix A.4): exponential
 * extinction along the ray segment. Light crossing a segment of length |I| keeps the
 * fraction exp(-|I|/distance) of itself; the rest is replaced by the background colour, and
 * the opacity rises towards 1 by the same fraction.
 * (shaders/build.rs reads shaders/rsl/standard only, so the shader collection has no volumes;
 * tests/build.rs generates Rust of it for the cross-check of the three back ends.)
 */
volume fog(float distance = 1; color background = 0;)
{
    /* distance <= 0: infinitely dense, nothing gets through */
    float lost = distance > 0 ? 1 - exp(-length(I) / distance) : 1;
    Ci = mix(Ci, background, lost);
    Oi = mix(Oi, color(1, 1, 1), lost);
}
