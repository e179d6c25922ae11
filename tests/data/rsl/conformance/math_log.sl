// test: log with one argument is the natural logarithm
// expect: r = 2.30258509
surface t_math_log(output varying float r = 0;)
{
    r = log(10);
}
