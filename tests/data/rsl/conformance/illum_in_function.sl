// test: illuminance inside a user function
// expect: Ci = 0.788857728, 0.783175391, 0.837195285
// tol: 0.0001
color lightsum(normal n)
{
    color c = 0;
    illuminance(P, n, PI / 2) {
        c += Cl * (normalize(L) . n);
    }
    return c;
}

surface t_illum_in_function()
{
    Ci = lightsum(N);
}
