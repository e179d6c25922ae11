// error: the result of a void function used as a value
// at: 11:9
void touch(output float x)
{
    x = 1;
}

surface d_void_value_used(output varying float r = 0;)
{
    float a = 0;
    r = touch(a);
}
