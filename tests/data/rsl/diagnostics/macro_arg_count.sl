// error: macro SQ takes 1 argument, given 2
// at: 7:9
#define SQ(x) ((x) * (x))

surface d_macro_arg_count(output varying float r = 0;)
{
    r = SQ(s, t);
}
