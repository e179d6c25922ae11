// test: array initializer {1, 2, 3}
// expect: r = 2
// expect: Ci = 2.5, 2.5, 2.5
surface t_array_init(output varying float r = 0;)
{
    float a[3] = {1.5, 2.5, 3.5};
    r = a[2] - a[0];
    Ci = a[1];
}
