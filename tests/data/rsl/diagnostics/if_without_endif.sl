// error: #if without a matching #endif
// at: 3:1
#if 1
surface d_if_without_endif()
{
    Ci = 1;
}
