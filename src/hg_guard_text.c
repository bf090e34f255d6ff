/* hg_guard_text.c - what the guard found, as a sentence (hg_guard_text.h). */
#include "hg_math.h"
#include "hg_guard_text.h"
#include "hg_params.h"
#include "hg_text.h"
#include "hg_units.h"

/* Name of the parameter spec_name on the chosen face (HAL or spec). */
static const char *param_name(const char *spec_name, int hal)
{
    return hal ? hg_params_hal_name(spec_name) : spec_name;
}

/* Append v * scale rounded to 3 decimals. */
static void add_num(char *buf, double v, double scale)
{
    double x = v * scale;
    if (isfinite(x) && fabs(x) < 1e12)
        x = floor(x * 1000.0 + 0.5) / 1000.0;
    hg_text_add_value(buf, HG_GUARD_TEXT_LEN, x);
}

/* Append the decimal digit string of a small index. */
static void add_index(char *buf, int k)
{
    char d[3] = {(char)('0' + (k / 10) % 10), (char)('0' + k % 10), 0};
    hg_text_add(buf, HG_GUARD_TEXT_LEN, k >= 10 ? d : d + 1);
}

void hg_guard_describe(const hg_guard_report *r, int hal, char buf[HG_GUARD_TEXT_LEN])
{
    static const char *const axis[6] = {"X", "Y", "Z", "A", "B", "C"};
    const unsigned long n = HG_GUARD_TEXT_LEN;
    const int joint = r->kind == HG_GUARD_CARRIAGE_JOINT;
    buf[0] = '\0';
    switch (r->kind) {
    case HG_GUARD_CARRIAGE_JOINT:
    case HG_GUARD_HEAD_JOINT:
        hg_text_add(buf, n, "bar ");
        add_index(buf, r->bar);
        hg_text_add(buf, n, " (joint ");
        add_index(buf, r->bar);
        hg_text_add(buf, n, ") at ");
        add_num(buf, r->value, HG_DEG_PER_RAD);
        hg_text_add(buf, n, joint ? " deg in its carriage joint, beyond the " : " deg in its head joint, beyond the ");
        add_num(buf, r->limit, HG_DEG_PER_RAD);
        hg_text_add(buf, n, " deg the joint allows (");
        hg_text_add(buf, n, param_name(joint ? "cone_carriage" : "cone_head", hal));
        hg_text_add(buf, n, ")");
        break;
    case HG_GUARD_BARS:
        hg_text_add(buf, n, "bars ");
        add_index(buf, r->bar);
        hg_text_add(buf, n, " and ");
        add_index(buf, r->other);
        hg_text_add(buf, n, " touch: their axes are ");
        add_num(buf, r->value, HG_MM_PER_M);
        hg_text_add(buf, n, " mm apart, less than the ");
        add_num(buf, r->limit, HG_MM_PER_M);
        hg_text_add(buf, n, " mm bar diameter (");
        hg_text_add(buf, n, param_name("d_bar", hal));
        hg_text_add(buf, n, ")");
        break;
    case HG_GUARD_REGION:
        if (!isfinite(r->value)) {
            hg_text_add(buf, n, "the state is not finite");
            break;
        }
        if (r->bar >= 0) {
            hg_text_add(buf, n, "carriage ");
            add_index(buf, r->bar);
        } else {
            hg_text_add(buf, n, "head ");
            hg_text_add(buf, n, r->other >= 0 && r->other < 6 ? axis[r->other] : "?");
        }
        hg_text_add(buf, n, " at ");
        add_num(buf, r->value, r->other >= 3 ? HG_DEG_PER_RAD : HG_MM_PER_M);
        hg_text_add(buf, n, r->other >= 3 ? " deg, beyond the " : " mm, beyond the ");
        add_num(buf, r->limit, r->other >= 3 ? HG_DEG_PER_RAD : HG_MM_PER_M);
        hg_text_add(buf, n, r->other >= 3 ? " deg" : " mm");
        hg_text_add(buf, n, " a machine with a broken bar is modelled to (it would strike the frame)");
        break;
    case HG_GUARD_THROUGH_STOP:
        hg_text_add(buf, n, "carriage ");
        add_index(buf, r->bar);
        hg_text_add(buf, n, " at ");
        add_num(buf, r->value, HG_MM_PER_M);
        hg_text_add(buf, n, " mm went through its hard stop at ");
        add_num(buf, r->limit, HG_MM_PER_M);
        hg_text_add(buf, n, " mm (");
        hg_text_add(buf, n, param_name(r->value < r->limit ? "stop_min" : "stop_max", hal));
        hg_text_add(buf, n, ")");
        break;
    default:
        break;
    }
}
