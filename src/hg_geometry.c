/* hg_geometry.c - what follows from the geometry alone (hg_geometry.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_geometry.h"

double hg_home_height(const hg_geometry *g)
{
    double d = g->lb_m - g->lp_m;
    return sqrt(g->l_m * g->l_m - d * d);
}

unsigned hg_geometry_fingerprint(const hg_geometry *g)
{
    const double f[7] = {g->l_m, g->lb_m, g->e_m, g->lp_m, g->cone_carriage_rad, g->cone_head_rad,
                         g->d_bar_m};
    unsigned h = 2166136261u;
    int i, k;
    for (i = 0; i < 7; i++) {
        unsigned long long bits;
        memcpy(&bits, &f[i], sizeof bits);
        for (k = 0; k < 8; k++, bits >>= 8)
            h = (h ^ (unsigned)(bits & 0xffu)) * 16777619u;
    }
    return h ? h : 1u;
}

int hg_geometry_mismatch(unsigned board_fp, unsigned own_fp, int *calls)
{
    if (board_fp == 0 || board_fp == own_fp) {
        *calls = 0;
        return 0;
    }
    if (*calls <= HG_GEOMETRY_MISMATCH_CALLS)
        (*calls)++;                   /* stops one past: the report comes once */
    return *calls == HG_GEOMETRY_MISMATCH_CALLS;
}
