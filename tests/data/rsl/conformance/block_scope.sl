// test: a variable declared in a block shadows the outer one only inside it
// expect: r = 1
// expect: g = 2
surface t_block_scope(output varying float r = 0; output varying float g = 0;)
{
    float x = 1;
    {
        float x = 2;
        g = x;
    }
    r = x;
}
