// test: array declaration, element assignment and indexing
// expect: r = 421
surface t_array_index(output varying float r = 0;)
{
    float a[3];
    a[0] = 1;
    a[1] = 2;
    a[2] = 4;
    r = a[0] + 10 * a[1] + 100 * a[2];
}
