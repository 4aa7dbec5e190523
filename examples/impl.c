/* The one translation unit that holds the library implementation for all examples. POSIX
   before any header, so that the frame budget of sps_world_advance_frame (examples/demo.c)
   reads the monotonic clock (sphsolid.h, CONFIG MACROS: SPHSOLID_WALL_SECONDS). */
#define _POSIX_C_SOURCE 200809L
#define SPHSOLID_IMPLEMENTATION
#include "../sphsolid.h"
