// test: summing an array in a for loop with a float index
// expect: r = 55
surface t_array_loop_sum(output varying float r = 0;)
{
    float a[5] = {1, 2, 3, 4, 5};
    uniform float i;
    r = 0;
    for (i = 0; i < 5; i += 1)
        r += a[i] * a[i];
}
