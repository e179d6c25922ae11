// error: assignment to the read-only global Ng in a surface shader
// at: 5:5
surface d_readonly_global()
{
    Ng = normal(0, 1, 0);
    Ci = 1;
}
