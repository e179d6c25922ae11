// error: indexing a variable that is not an array
// at: 6:9
surface d_index_non_array(output varying float r = 0;)
{
    float a = 2;
    r = a[0];
}
