// error: break outside a loop
// at: 6:5
surface d_break_outside_loop()
{
    Ci = 1;
    break;
}
