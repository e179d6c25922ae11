/*
 * depthcue — RenderMan Interface 3.2 standard volume shader (Appendix A.4): a linear blend
 * towards the background colour with depth, none before mindistance, complete beyond
 * maxdistance. The depth is the camera-space z of P (the distance along the viewing axis:
 * Table 4.10 gives mindistance and maxdistance as distances; the spec's code writes
 * depth(P), which some renderers normalize by the clipping planes).
 */
volume depthcue(float mindistance = 0, maxdistance = 1; color background = 0;)
{
    float z = zcomp(transform("camera", P));
    float span = maxdistance - mindistance;
    float d = 0;
    if (span > 0) {
        d = clamp((z - mindistance) / span, 0, 1);
    } else {
        d = z >= maxdistance ? 1 : 0;
    }
    Ci = mix(Ci, background, d);
    Oi = mix(Oi, color(1, 1, 1), d);
}
