// error: assignment to something that is not a variable (a function call)
// at: 5:5
surface d_non_lvalue_assign()
{
    xcomp(P) = 1;
    Ci = 1;
}
