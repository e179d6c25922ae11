// test: illuminance with a category visits only lights of that category (table1 lights have none)
// expect: r = 0
// expect: Ci = 0.25, 0.25, 0.25
surface t_illum_category(output varying float r = 0;)
{
    r = 0;
    illuminance("backlight", P) {
        r += 1;
    }
    Ci = 0.25;
}
