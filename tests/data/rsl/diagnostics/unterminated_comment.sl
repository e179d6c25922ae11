// error: unterminated block comment
// at: 6:5
surface d_unterminated_comment()
{
    Ci = 1;
    /* this comment never ends
}
