// test: random() is in [0, 1)
// expect: r = 1
surface t_math_random_range(output varying float r = 0;)
{
    float x = random();
    r = (x >= 0 && x < 1) ? 1 : 0;
}
