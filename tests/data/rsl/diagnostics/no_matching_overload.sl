// error: no overload of normalize takes a string
// at: 5:16
surface d_no_matching_overload()
{
    vector v = normalize("up");
    Ci = color(xcomp(v), ycomp(v), zcomp(v));
}
