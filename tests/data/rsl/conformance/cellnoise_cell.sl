// test: cellnoise is constant within a unit cell
// expect: r = 0
// expect: g = 0
surface t_cellnoise_cell(output varying float r = 0; output varying float g = 0;)
{
    r = cellnoise(point(1.1, 2.2, 3.3)) - cellnoise(point(1.9, 2.05, 3.99));
    g = cellnoise(4.2) - cellnoise(4.8);
}
