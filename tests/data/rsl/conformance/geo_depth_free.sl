// test: length and the dot-product form of the squared length agree
// expect: r = 0
surface t_geo_depth_free(output varying float r = 0;)
{
    vector d = vector(1, 2, 2);
    r = length(d) * length(d) - d . d;
}
