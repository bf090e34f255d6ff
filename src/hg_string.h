/* hg_string.h - memcpy/memset/memcmp/strcmp for the core: LinuxCNC's
 * rtapi_string.h in a realtime module (RTAPI defined), <string.h> on the
 * host. Core files include this instead of <string.h>. */
#ifndef HG_STRING_H
#define HG_STRING_H
#ifdef RTAPI
#include "rtapi_string.h"
#else
#include <string.h>
#endif
#endif
