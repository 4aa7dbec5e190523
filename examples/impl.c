/* The one translation unit that holds the library implementation for all examples. */
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
