/*
 * null — RenderMan Interface 3.2 standard surface: transparent and black; the surface
 * shows what lies behind it.
 */
surface null()
{
    Oi = 0;
    Ci = 0;
}
