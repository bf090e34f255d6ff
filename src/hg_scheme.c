/* hg_scheme.c - names and tableaux of the integration schemes (hg_scheme.h). */
#include "hg_string.h"
#include "hg_scheme.h"

static const char *const names[HG_INTEGRATOR_COUNT] = {
    "improved-euler", "heun", "rk4",
};

const char *hg_integrator_name(hg_integrator which)
{
    return (int)which >= 0 && which < HG_INTEGRATOR_COUNT ? names[which] : 0;
}

int hg_integrator_default(void)
{
    return HG_INTEGRATOR_DEFAULT;
}

int hg_integrator_from_name(const char *name)
{
    int i;
    for (i = 0; name && i < HG_INTEGRATOR_COUNT; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

/* RK4's stage offsets (c_i dt) and weights (b_i); Heun's are the first two */
static const double rk4_c[4] = {0.0, 0.5, 0.5, 1.0};
static const double rk4_b[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
static const double heun_c[2] = {0.0, 1.0};
static const double heun_b[2] = {0.5, 0.5};

int hg_scheme_tableau(hg_integrator scheme, const double **c, const double **b)
{
    switch (scheme) {
    case HG_INTEGRATOR_HEUN:
        *c = heun_c, *b = heun_b;
        return 2;
    case HG_INTEGRATOR_RK4:
        *c = rk4_c, *b = rk4_b;
        return 4;
    default:
        return 0;
    }
}
