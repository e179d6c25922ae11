// error: type mismatch in assignment: a color cannot be assigned to a float
// at: 6:9
surface d_assign_type_mismatch()
{
    float f = 0;
    f = color(1, 0, 0);
    Ci = f;
}
