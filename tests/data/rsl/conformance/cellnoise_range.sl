// test: cellnoise is in [0, 1) and differs between neighbouring cells
// expect: r = 1
// expect: g = 1
surface t_cellnoise_range(output varying float r = 0; output varying float g = 0;)
{
    float a = cellnoise(point(0.5, 0.5, 0.5));
    float b = cellnoise(point(1.5, 0.5, 0.5));
    r = (a >= 0 && a < 1 && b >= 0 && b < 1) ? 1 : 0;
    g = (a != b) ? 1 : 0;
}
