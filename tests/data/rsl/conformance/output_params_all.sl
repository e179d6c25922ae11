// test: output parameters of every triple type
// expect: oc = 0.1, 0.2, 0.3
// expect: op = 0.5, 0.5, 0
// expect: ov = 0.5, 0.5, -3
// expect: on = 0, 0, 1
surface t_output_params_all(output varying color oc = 0; output varying point op = 0; output varying vector ov = 0; output varying normal on = 0;)
{
    oc = color(0.1, 0.2, 0.3);
    op = P;
    ov = I;
    on = N;
}
