// test: color(x) and the typecast color x fill all components
// expect: c = 0.5, 0.5, 0.5
// expect: Ci = 0.25, 0.25, 0.25
surface t_ctor_color_float(output varying color c = 0;)
{
    c = color(0.5);
    Ci = color 0.25;
}
