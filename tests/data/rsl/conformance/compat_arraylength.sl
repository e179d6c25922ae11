// test: arraylength of a fixed-size array, also through an unsized function parameter (PRMan 13)
// expect: Ci = 3, 6, 0
float total(float a[]) { float i, t = 0; for (i = 0; i < arraylength(a); i += 1) t += a[i]; return t; }
surface t_compat_arraylength()
{
    float a[3] = {1, 2, 3};
    Ci = color(arraylength(a), total(a), 0);
}
