/* hg_plant.c - the registry of plants and what every plant shares (hg_plant.h). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_plant.h"
#include "hg_plant_hexaglide.h"

/* Append only: a record names its plant by the index. */
static const hg_plant *const plants[] = {
    &hg_plant_hexaglide,
};

const hg_plant *hg_plant_at(int i)
{
    return i >= 0 && i < (int)(sizeof plants / sizeof plants[0]) ? plants[i] : 0;
}

int hg_plant_find(const char *name)
{
    int i;
    for (i = 0; name && hg_plant_at(i); i++)
        if (strcmp(hg_plant_at(i)->name, name) == 0)
            return i;
    return -1;
}

int hg_plant_variant(const hg_plant *p, const char *name)
{
    int i;
    if (!name)
        return p->default_variant;
    for (i = 0; i < p->nvariants; i++)
        if (strcmp(p->variants[i], name) == 0)
            return i;
    return -1;
}

unsigned hg_plant_switches(double pos, double limit_min, double limit_max, double home_at)
{
    unsigned s = 0;
    if (!isfinite(pos))
        return HG_SW_MIN | HG_SW_MAX;
    if (pos <= limit_min)
        s |= HG_SW_MIN;
    if (pos >= limit_max)
        s |= HG_SW_MAX;
    if (pos >= home_at)
        s |= HG_SW_HOME;
    return s;
}

const hg_param_info *hg_plant_params_table(int plant, int *count)
{
    const hg_plant *p = hg_plant_at(plant);
    *count = 0;
    return p ? p->table(count) : 0;
}

int hg_plant_params_defaults(int plant, hg_plant_params *v)
{
    const hg_plant *p = hg_plant_at(plant);
    if (!p)
        return -1;
    p->defaults(v);
    return 0;
}

const char *hg_plant_name_at(int plant)
{
    const hg_plant *p = hg_plant_at(plant);
    return p ? p->name : 0;
}

int hg_plant_variant_named(int plant, const char *name)
{
    const hg_plant *p = hg_plant_at(plant);
    return p ? hg_plant_variant(p, name) : -1;
}
