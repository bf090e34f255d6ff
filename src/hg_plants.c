/* hg_plants.c - the registry of plants (hg_plant.h): the one file that names
 * every built-in plant, above them; the interface (hg_plant.c) knows none. */
#include "hg_string.h"
#include "hg_plant.h"
#include "hg_plant_hexaglide.h"
#include "hg_plant_serial.h"

/* Append only: a record names its plant by the index. */
static const hg_plant *const plants[] = {
    &hg_plant_hexaglide,
    &hg_plant_serial,
};
#define BUILT_IN ((int)(sizeof plants / sizeof plants[0]))

/* Plants registered at run time (hg_plant_register), after the built-in ones. */
static const hg_plant *added[HG_PLANTS_ADDED_MAX];
static int nadded;

const hg_plant *hg_plant_at(int i)
{
    if (i >= 0 && i < BUILT_IN)
        return plants[i];
    return i >= BUILT_IN && i < BUILT_IN + nadded ? added[i - BUILT_IN] : 0;
}

int hg_plant_register(const hg_plant *p)
{
    if (!p || !p->name || hg_plant_find(p->name) >= 0 || nadded >= HG_PLANTS_ADDED_MAX ||
        p->model_bytes > sizeof(hg_plant_model) || p->data_bytes > sizeof(hg_plant_data) ||
        p->state_bytes > p->data_bytes)
        return -1;
    added[nadded] = p;
    return BUILT_IN + nadded++;
}

int hg_plant_find(const char *name)
{
    int i;
    for (i = 0; name && hg_plant_at(i); i++)
        if (strcmp(hg_plant_at(i)->name, name) == 0)
            return i;
    return -1;
}
