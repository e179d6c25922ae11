// error: illuminate is only allowed in a light shader
// at: 6:5
surface d_illuminate_outside_light()
{
    Ci = 0;
    illuminate(P) {
        Ci = 1;
    }
}
