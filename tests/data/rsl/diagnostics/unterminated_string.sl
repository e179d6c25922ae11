// error: unterminated string literal
// at: 5:16
surface d_unterminated_string()
{
    string a = "abc;
    Ci = 1;
}
