/*
 * parquet — wooden planks in a basket-weave parquet on (s, t), each with its own
 * grain. Port of shaders/src/surfaces/parquet.rs. Square tiles of tilesize hold
 * `planks` planks, the plank direction alternating between s and t like a
 * checkerboard. Every plank has growth rings (smoothstep profile, as in wood) around
 * an axis along the plank, placed by the plank's vector cellnoise and perturbed by
 * two octaves of snoise, fine grain along the plank and a per-plank tint
 * (±plankvary/2). Grooves of groovewidth (a fraction of the plank width) run around
 * every plank, box-filtered with filterstep; plastic lighting with the highlight
 * suppressed in the grooves, Oi = Os.
 */
surface parquet(
    uniform float Ka = 1;
    uniform float Kd = 0.75;
    uniform float Ks = 0.15;
    uniform float roughness = 0.1;
    uniform color specularcolor = 1;
    uniform float tilesize = 0.25;     /* side of a basket-weave tile in (s, t) */
    uniform float planks = 3;          /* planks per tile (rounded, at least 1) */
    uniform float groovewidth = 0.05;  /* groove width, fraction of the plank width */
    uniform float ringscale = 6;       /* growth rings per plank width */
    uniform float ringnoise = 0.6;     /* noise perturbing the rings, in rings */
    uniform float grainscale = 40;     /* grain frequency across the plank */
    uniform float plankvary = 0.25;    /* relative colour variation between planks */
    uniform color lightwood = color (0.76, 0.52, 0.29);
    uniform color darkwood = color (0.45, 0.26, 0.11);
    uniform color groovecolor = color (0.08, 0.05, 0.03);)
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);

    uniform float nplanks = max(round(planks), 1);
    float ss = s / tilesize;
    float tt = t / tilesize;
    float ti = floor(ss);
    float tj = floor(tt);
    float fs = ss - ti;
    float ft = tt - tj;

    /* Basket weave: planks run along s in "even" tiles and along t in "odd" ones. */
    float along, across;
    if (mod(ti + tj, 2) >= 1) {
        along = ft;
        across = fs * nplanks;
    } else {
        along = fs;
        across = ft * nplanks;
    }
    float pk = floor(across);
    float w = across - pk;

    /* Grooves along the plank sides (in plank widths) and at the plank ends (the
       same width in tile units). */
    uniform float gw = groovewidth * 0.5;
    float side = filterstep(gw, w) - filterstep(1 - gw, w);
    uniform float gl = gw / nplanks;
    float end = filterstep(gl, along) - filterstep(1 - gl, along);
    float in_plank = side * end;

    /* Plank identity: its tile, orientation and index (cell centres). */
    vector rnd = vector cellnoise(point (ti + 0.5, tj + 0.5, pk + 0.5));
    /* Plank-local coordinates in plank widths: x across, z along, depth 0 = surface. */
    float x = w - 0.5;
    float z = along * nplanks;
    float axis_x = (ycomp(rnd) - 0.5) * 4;
    float axis_depth = 0.5 + zcomp(rnd) * 2;
    /* Each plank reads the noise at its own place. */
    vector seed = rnd * 97;
    point q = point (x, 0, z * 0.25) + seed;
    float pert = snoise(q * 1.5) + 0.5 * snoise(q * 3);
    float dx = x - axis_x;
    float r = ringscale * sqrt(dx * dx + axis_depth * axis_depth) + ringnoise * pert;
    float f = r - floor(r);
    float ring = smoothstep(0, 0.8, f) - smoothstep(0.83, 1, f);
    /* Fine grain, stretched along the plank. */
    float grain = 0.85 + 0.15 * snoise(point (grainscale * x, 0, grainscale * (1.0 / 24.0) * z) + seed);
    float tint = 1 + plankvary * (xcomp(rnd) - 0.5);
    color wood = (lightwood + (darkwood - lightwood) * ring) * (grain * tint);
    color Ct = groovecolor + (wood - groovecolor) * in_plank;

    /* Plastic, with the highlight weighted by in_plank. */
    color spec = 0;
    if (Ks != 0)
        spec = specular(Nf, V, roughness);
    Oi = Os;
    Ci = Os * (Ct * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * spec * in_plank);
}
