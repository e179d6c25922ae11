// error: a triple constructor needs 3 components, given 2
// at: 5:21
surface d_triple_component_count()
{
    color c = color (1, 2);
    Ci = c;
}
