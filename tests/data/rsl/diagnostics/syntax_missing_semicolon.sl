// error: syntax error: missing ";" (reported at the unexpected token)
// at: 6:5
surface d_syntax_missing_semicolon()
{
    float a = 1
    float b = 2;
    Ci = a + b;
}
