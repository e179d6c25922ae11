// error: continue 2 inside only one loop
// at: 8:13
surface d_continue_level_too_deep(output varying float r = 0;)
{
    float i;
    for (i = 0; i < 4; i += 1) {
        if (i == 2)
            continue 2;
        r += i;
    }
}
