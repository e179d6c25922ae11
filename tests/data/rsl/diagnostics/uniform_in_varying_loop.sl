// error: a uniform output argument assigned inside a loop whose condition is varying
// at: 8:9
void count(output uniform float k)
{
    float i;
    for (i = 0; i < s * 10; i += 1)
    {
        k += 1;
    }
}
surface d_uniform_in_varying_loop()
{
    uniform float k = 0;
    count(k);
    Ci = k;
}
