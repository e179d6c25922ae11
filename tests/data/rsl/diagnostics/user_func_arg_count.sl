// error: wrong number of arguments to a user function
// at: 10:9
float twice(float x)
{
    return 2 * x;
}

surface d_user_func_arg_count(output varying float r = 0;)
{
    r = twice(s, t);
}
