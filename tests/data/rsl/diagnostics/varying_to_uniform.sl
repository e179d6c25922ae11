// error: assigning a varying value (s) to a uniform variable
// at: 6:5
surface d_varying_to_uniform()
{
    uniform float k = 0;
    k = s * 2;
    Ci = k;
}
