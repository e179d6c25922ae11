// error: call of an undefined function "frobnicate"
// at: 5:9
surface d_undefined_function(output varying float r = 0;)
{
    r = frobnicate(s);
}
