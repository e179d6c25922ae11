// error: unknown identifier "foo"
// at: 5:10
surface d_unknown_identifier()
{
    Ci = foo * 2;
}
