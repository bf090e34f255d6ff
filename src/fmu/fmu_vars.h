/* fmu_vars.h - the FMU's variables: one table for the FMI glue
 * (fmu_fmi3.c: value references, types, who may set what) and for the
 * generator of modelDescription.xml (fmu_gen.c), so the description and
 * the binary cannot disagree; the model parameters come from the plant's
 * own table (fmu_plant.h). Value reference = index in the list below. */
#ifndef FMU_VARS_H
#define FMU_VARS_H

#include "fmu_plant.h"

typedef enum { FMU_FLOAT64, FMU_INT32, FMU_UINT32, FMU_ENUM, FMU_BOOLEAN } fmu_type;
typedef enum { FMU_INDEPENDENT, FMU_PARAMETER, FMU_INPUT, FMU_OUTPUT } fmu_causality;

/* Groups of variables, in value-reference order; per-joint groups have
 * FMU_JOINTS elements (name_0 .. name_5), the head groups 3, FMU_G_PARAM
 * one per model parameter. */
typedef enum {
    FMU_G_TIME,
    FMU_G_MODEL, FMU_G_INTEGRATOR, FMU_G_SUBSTEPS, FMU_G_PERIOD, FMU_G_ENC_SCALE,
    FMU_G_DAC, FMU_G_ESTOP, FMU_G_RESET, FMU_G_AMP_ENABLE,
    FMU_G_COUNT, FMU_G_POSITION, FMU_G_INDEX, FMU_G_LIMIT_MIN, FMU_G_LIMIT_MAX, FMU_G_HOME,
    FMU_G_FAULT, FMU_G_FAULT_CODE, FMU_G_AMPS_ON,
    FMU_G_Z, FMU_G_ZD, FMU_G_HEAD_POS, FMU_G_HEAD_ROT, FMU_G_CURRENT, FMU_G_FORCE,
    FMU_G_PARAM,
    FMU_G_N
} fmu_group;

#define FMU_NAME_LEN 48
#define FMU_TEXT_LEN 256

/* One variable, as modelDescription.xml declares it. */
typedef struct {
    char name[FMU_NAME_LEN];
    char description[FMU_TEXT_LEN];
    fmu_group group;
    int k;                            /* element of the group */
    fmu_type type;
    fmu_causality causality;
    const char *variability;          /* "fixed", "continuous", "discrete" */
    const char *unit;                 /* 0: none */
    const char *display_unit;         /* 0: none */
    double display_factor;
    int has_range;                    /* min, max declared (fmi3Set refuses a value outside) */
    double min, max;
    double quantum;                   /* > 0: fmi3Set takes only whole multiples of it (period: 1 ns) */
    const char *declared_type;        /* enumerations: "Model", "Integrator"; else 0 */
} fmu_var;

/* The rule of variable v for value x (fmi3Set, and a deserialized
 * state's values): 0 when it takes x, else -1 with the rule in why (len
 * bytes). Parameters: not NaN, an item of an enumeration, within min and
 * max, a whole multiple of quantum (period: whole ns), each rule the
 * core's words (a model parameter's: the core's check of x with the other
 * parameters at vals[], the values by value reference). Inputs and
 * outputs: any value. The rules between parameters are the core's, at
 * fmi3ExitInitializationMode. */
int fmu_var_refuse(const fmu_var *v, double x, const double *vals, char *why, size_t len);

/* The shortest decimal text that reads back as x (at most 17 digits). */
const char *fmu_num(char buf[32], double x);

/* Number of variables (value references 0 .. count-1). */
unsigned fmu_var_count(void);

/* Variable vr into *v: 0, or -1 when vr names none. */
int fmu_var_get(unsigned vr, fmu_var *v);

/* Value reference of element k of group g. */
unsigned fmu_var_vr(fmu_group g, int k);

/* The start value of every variable (v[vr], fmu_var_count() entries; 0
 * for outputs and time): 0, or -1 (out of memory). */
int fmu_vars_start(double *v);

/* The instantiation token of this variable list and its starts,
 * "{hexaglide-<16 hex digits>}"; 0 or -1 (out of memory). */
#define FMU_TOKEN_LEN 48
int fmu_vars_token(char token[FMU_TOKEN_LEN]);

/* FNV-1a hash of n bytes (the serialized FMU state's checksum). */
unsigned long long fmu_hash(const void *data, size_t n);

/* Names of the enumeration types' items, for the description. */
int fmu_enum_count(const char *declared_type);
const char *fmu_enum_item(const char *declared_type, int i);

#endif
