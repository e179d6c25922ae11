// test: cellnoise values: 1D, 2D, 3D (lattice hash of the shading workload)
// expect: r = 0.301803291
// expect: g = 0.182492256
// expect: b = 0.167402148
surface t_cellnoise_value(output varying float r = 0; output varying float g = 0; output varying float b = 0;)
{
    r = cellnoise(3.5);
    g = cellnoise(s, t + 2);
    b = cellnoise(point(-1.5, 2.5, 7.25));
}
