// error: wrong number of arguments: sqrt takes 1, given 2
// at: 5:9
surface d_wrong_arg_count(output varying float r = 0;)
{
    r = sqrt(1, 2);
}
