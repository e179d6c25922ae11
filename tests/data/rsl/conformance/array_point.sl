// test: array of points, element update with +=
// expect: p = 2, 4, 6
surface t_array_point(output varying point p = 0;)
{
    point a[2] = {point(1, 2, 3), point(0, 0, 0)};
    a[1] += a[0] * 2;
    p = a[1];
}
