// test: a nested function reads and writes an enclosing variable declared extern
// expect: r = 3.5
surface t_func_extern(output varying float r = 0;)
{
    float total = 1;
    void add(float x)
    {
        extern float total;
        total += x;
    }
    add(2);
    add(s);
    r = total;
}
