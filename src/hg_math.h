/* hg_math.h - the C math library the core may use, from the right place:
 * LinuxCNC's rtapi_math.h when compiled as a realtime module (RTAPI is
 * defined by Makefile.modinc), <math.h> on the host (CLI, tests, fuzzers).
 * Core files include this instead of <math.h>; the realtime modules' list
 * of undefined symbols is checked against rtapi_math's functions
 * (tests/check/test_rt_symbols). */
#ifndef HG_MATH_H
#define HG_MATH_H
#ifdef RTAPI
#include "rtapi_math.h"
#else
#include <math.h>
#endif
#endif
