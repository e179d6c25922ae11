// test: ctransform to "YIQ" and back is the identity
// expect: c = 0.3000339, 0.5998047, 0.9006933
// tol: 0.0001
surface t_ctransform_roundtrip(output varying color c = 0;)
{
    c = ctransform("YIQ", "rgb", ctransform("rgb", "YIQ", color(0.3, 0.6, 0.9)));
}
