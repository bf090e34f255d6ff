/* hg_plant_hexaglide.h - the Hexaglide as a plant of the virtual board
 * (hg_plant.h), and the sizes of its own types for bindings. */
#ifndef HG_PLANT_HEXAGLIDE_H
#define HG_PLANT_HEXAGLIDE_H

#include "hg_plant.h"
#include "hg_model.h"
#include "hg_stability.h"

extern const hg_plant hg_plant_hexaglide;

/* The Hexaglide's model and data in a plant's storage (for tools above
 * the board that look inside the machine: soak's energy balance). */
const hg_model *hg_hexaglide_model(const hg_plant_model *m);
const hg_data *hg_hexaglide_data(const hg_plant_data *d);

/* The substeps (substeps_min..substeps_max) the scheme needs to integrate
 * the Hexaglide p stably at period_s (hg_stability_check_axes on one
 * carriage: every carriage is alike); writes *out. 0, or HG_ERR_STIFF. */
int hg_stability_check(const hg_params *p, hg_integrator scheme, double period_s, unsigned substeps_min,
                       unsigned substeps_max, hg_stability *out);

/* sizeof the Hexaglide's types, for bindings that mirror them
 * (tools/hexaglide.py): 4 hg_model, 5 hg_data, 6 hg_params,
 * 12 HG_DATA_STATE_BYTES (hg_data before its scratch); else 0. */
unsigned long hg_hexaglide_sizeof(int which);

#endif
