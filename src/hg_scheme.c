/* hg_scheme.c - names of the integration schemes (hg_scheme.h). */
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
