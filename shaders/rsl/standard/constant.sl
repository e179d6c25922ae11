/*
 * constant — RenderMan Interface 3.2 standard surface: the surface colour, unlit.
 *   Oi = Os, Ci = Os·Cs
 */
surface constant()
{
    Oi = Os;
    Ci = Os * Cs;
}
