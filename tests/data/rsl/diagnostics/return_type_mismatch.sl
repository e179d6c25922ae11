// error: return type mismatch: a float function returns a string
// at: 5:12
float label(float x)
{
    return "big";
}

surface d_return_type_mismatch(output varying float r = 0;)
{
    r = label(s);
}
