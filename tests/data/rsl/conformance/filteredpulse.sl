// test: filteredpulse is the difference of two filtersteps; a constant argument gives the pulse
// expect: r = 0.5
// expect: g = 1
// expect: b = 0
surface t_filteredpulse(output varying float r = 0; output varying float g = 0; output varying float b = 0;)
{
    r = filteredpulse(0.25, 0.75, s);
    g = filteredpulse(0.25, 0.75, 0.5);
    b = filteredpulse(0.25, 0.75, 0.9);
}
