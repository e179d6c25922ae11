// error: included file not found
// at: 3:10
#include "does_not_exist.h"

surface d_bad_include()
{
    Ci = 1;
}
