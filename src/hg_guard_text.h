/* hg_guard_text.h - a guard report (hg_guard.h) as one sentence for the
 * messages of the board, the kinematics and the CLI; the parameters it
 * names come from the Hexaglide's table (hg_params.h). Pure C, no stdio. */
#ifndef HG_GUARD_TEXT_H
#define HG_GUARD_TEXT_H

#include "hg_guard.h"

/* What r found as one sentence (mm and degrees, 3 decimals), naming the
 * bar(s) and the limit's parameter: by its HAL name ("cone-head") when
 * hal is 1, by its spec name ("cone_head") when 0. Empty for kind NONE. */
#define HG_GUARD_TEXT_LEN 200
void hg_guard_describe(const hg_guard_report *r, int hal, char buf[HG_GUARD_TEXT_LEN]);

#endif
