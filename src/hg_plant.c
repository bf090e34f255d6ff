/* hg_plant.c - what every plant shares (hg_plant.h); the registry of plants is hg_plants.c. */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_plant.h"

int hg_plant_variant(const hg_plant *p, const char *name)
{
    return name ? p->variant_of(name) : p->default_variant;
}

int hg_plant_param(const hg_plant *p, int variant, int i, hg_param_info *out)
{
    return i >= 0 && i < p->nparams(variant) ? p->param(variant, i, out) : -1;
}

int hg_plant_param_find(const hg_plant *p, int variant, const char *name)
{
    hg_param_info e;
    int i, n = p->nparams(variant);
    for (i = 0; name && i < n; i++)
        if (p->param(variant, i, &e) == 0 && strcmp(e.name, name) == 0)
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

int hg_plant_nparams_at(int plant, int variant)
{
    const hg_plant *p = hg_plant_at(plant);
    char buf[HG_PLANT_TEXT_LEN];
    return p && p->variant_name(variant, buf, (int)sizeof buf) == 0 ? p->nparams(variant) : 0;
}

int hg_plant_channels_at(int plant, int variant)
{
    return hg_plant_nparams_at(plant, variant) ? hg_plant_at(plant)->channels(variant) : 0;
}

int hg_plant_param_at(int plant, int variant, int i, hg_param_info *out)
{
    const hg_plant *p = hg_plant_at(plant);
    return p && i < hg_plant_nparams_at(plant, variant) ? hg_plant_param(p, variant, i, out) : -1;
}

int hg_plant_defaults_at(int plant, int variant, hg_plant_params *v)
{
    const hg_plant *p = hg_plant_at(plant);
    if (!hg_plant_nparams_at(plant, variant))
        return -1;
    p->defaults(variant, v);
    return 0;
}

const char *hg_plant_name_at(int plant)
{
    const hg_plant *p = hg_plant_at(plant);
    return p ? p->name : 0;
}

const char *hg_plant_ini_section_at(int plant)
{
    const hg_plant *p = hg_plant_at(plant);
    return p ? p->ini_section : 0;
}

int hg_plant_variant_named(int plant, const char *name)
{
    const hg_plant *p = hg_plant_at(plant);
    return p ? hg_plant_variant(p, name) : -1;
}
