// error: redefinition of local variable "a" in the same scope
// at: 6:11
surface d_redefinition()
{
    float a = 1;
    float a = 2;
    Ci = a;
}
