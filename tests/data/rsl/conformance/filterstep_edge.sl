// test: filterstep at its edge is 0.5 (filter width |ds/dx| + |ds/dy| = 1)
// expect: r = 0.5
surface t_filterstep_edge(output varying float r = 0;)
{
    r = filterstep(0.5, s);
}
