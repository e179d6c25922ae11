// error: type mismatch in a parameter default: a string for a float
// at: 3:41
surface d_param_default_type(float Kd = "half";)
{
    Ci = Kd;
}
