// error: Cl is only defined inside illuminance in a surface shader
// at: 5:10
surface d_cl_outside_illuminance()
{
    Ci = Cl;
}
