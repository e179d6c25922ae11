// error: an output parameter is passed an expression that is not a variable
// at: 10:12
void setone(output float x)
{
    x = 1;
}

surface d_output_arg_not_lvalue()
{
    setone(s + 1);
    Ci = s;
}
