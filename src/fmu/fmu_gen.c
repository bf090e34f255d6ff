/* fmu_gen.c - writes the FMU's modelDescription.xml (FMI 3.0) from the
 * variable table (fmu_vars.h) and the plant's parameter table
 * (fmu_plant.h), at build time: every parameter's name, unit, default and
 * description has one owner, the core's table. Units are declared in
 * <UnitDefinitions> with their SI base units (parsed from the unit text)
 * and the display unit LinuxCNC shows them in.
 *   fmu-gen              modelDescription.xml on stdout
 *   fmu-gen --markdown   the variables as a Markdown table (docs/fmu.md) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmu_vars.h"

/* SI base units of the FMI <BaseUnit> element, in its attribute order. */
#define NBASE 8
static const char *const base_names[NBASE] = {"kg", "m", "s", "A", "K", "mol", "cd", "rad"};

/* One unit symbol: exponents of the base units and a factor to them. */
typedef struct {
    const char *symbol;
    int exp[NBASE];
    double factor;
} symbol_info;

static const symbol_info symbols[] = {
    {"kg", {1, 0, 0, 0, 0, 0, 0, 0}, 1},   {"m", {0, 1, 0, 0, 0, 0, 0, 0}, 1},
    {"s", {0, 0, 1, 0, 0, 0, 0, 0}, 1},    {"A", {0, 0, 0, 1, 0, 0, 0, 0}, 1},
    {"rad", {0, 0, 0, 0, 0, 0, 0, 1}, 1},  {"rev", {0, 0, 0, 0, 0, 0, 0, 1}, 2 * M_PI},
    {"N", {1, 1, -2, 0, 0, 0, 0, 0}, 1},   {"V", {1, 2, -3, -1, 0, 0, 0, 0}, 1},
    {"ohm", {1, 2, -3, -2, 0, 0, 0, 0}, 1}, {"H", {1, 2, -2, -2, 0, 0, 0, 0}, 1},
    {"1", {0, 0, 0, 0, 0, 0, 0, 0}, 1},
};

/* A unit in base units. */
typedef struct {
    const char *name;
    int exp[NBASE];
    double factor;
    const char *display[4];           /* display units of it */
    double display_factor[4];
    int ndisplay;
} unit_info;

#define MAX_UNITS 64

/* Parse "N s/m", "kg m^2", "m/s^2", "1/rev" into u: 0, or -1 naming the unknown symbol. */
static int parse_unit(const char *text, unit_info *u)
{
    char buf[64], *tok, *save = 0;
    int i, sign = 1;
    memset(u->exp, 0, sizeof u->exp);
    u->factor = 1;
    snprintf(buf, sizeof buf, "%s", text);
    for (tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(0, " ", &save)) {
        char *slash;
        do {
            char *caret;
            int power = 1;
            size_t j;
            slash = strchr(tok, '/');
            if (slash)
                *slash = 0;
            caret = strchr(tok, '^');
            if (caret) {
                *caret = 0;
                power = atoi(caret + 1);
            }
            for (j = 0; j < sizeof symbols / sizeof symbols[0] && strcmp(symbols[j].symbol, tok) != 0; j++)
                ;
            if (*tok && j == sizeof symbols / sizeof symbols[0]) {
                fprintf(stderr, "fmu-gen: unit '%s': unknown symbol '%s'; add it to the symbols of "
                                "src/fmu/fmu_gen.c\n", text, tok);
                return -1;
            }
            if (*tok) {
                for (i = 0; i < NBASE; i++)
                    u->exp[i] += sign * power * symbols[j].exp[i];
                u->factor *= pow(symbols[j].factor, sign * power);
            }
            if (slash) {
                sign = -1;            /* everything after the '/' is in the denominator */
                tok = slash + 1;
            }
        } while (slash);
    }
    return 0;
}

/* The unit called name in the list, added if new; 0 after a message. */
static unit_info *unit_of(unit_info *units, int *n, const char *name)
{
    int i;
    for (i = 0; i < *n; i++)
        if (!strcmp(units[i].name, name))
            return &units[i];
    if (*n == MAX_UNITS) {
        fprintf(stderr, "fmu-gen: more than %d units\n", MAX_UNITS);
        return 0;
    }
    memset(&units[*n], 0, sizeof units[*n]);
    units[*n].name = name;
    if (parse_unit(name, &units[*n]))
        return 0;
    return &units[(*n)++];
}

/* Add display unit d (factor f) to u; -1 if u has it with another factor. */
static int add_display(unit_info *u, const char *d, double f)
{
    int i;
    for (i = 0; i < u->ndisplay; i++)
        if (!strcmp(u->display[i], d)) {
            if (u->display_factor[i] == f)
                return 0;
            fprintf(stderr, "fmu-gen: display unit %s of %s with two factors (%.17g, %.17g)\n", d, u->name,
                    u->display_factor[i], f);
            return -1;
        }
    if (u->ndisplay == 4) {
        fprintf(stderr, "fmu-gen: too many display units of %s\n", u->name);
        return -1;
    }
    u->display[u->ndisplay] = d;
    u->display_factor[u->ndisplay++] = f;
    return 0;
}

/* The shortest decimal text that reads back as v (at most 17 digits). */
static const char *num(char buf[32], double v)
{
    return fmu_num(buf, v);
}

/* s with the XML attribute specials escaped. */
static void put_escaped(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
    }
}

/* FMI element name of a type. */
static const char *type_element(fmu_type t)
{
    static const char *const names[] = {"Float64", "Int32", "UInt32", "Enumeration", "Boolean"};
    return names[t];
}

/* FMI causality attribute. */
static const char *causality_name(fmu_causality c)
{
    static const char *const names[] = {"independent", "parameter", "input", "output"};
    return names[c];
}

/* A start value as FMI writes it for type t. */
static const char *start_text(char buf[32], fmu_type t, double v)
{
    if (t == FMU_BOOLEAN)
        return v != 0 ? "true" : "false";
    if (t == FMU_FLOAT64)
        return num(buf, v);
    snprintf(buf, 32, "%lld", (long long)v);
    return buf;
}

/* Every unit the variables use, with their display units; 0 or -1. */
static int collect_units(unit_info *units, int *n)
{
    unsigned vr, count = fmu_var_count();
    *n = 0;
    if (!unit_of(units, n, "s"))      /* the period, the time */
        return -1;
    for (vr = 0; vr < count; vr++) {
        fmu_var v;
        unit_info *u;
        fmu_var_get(vr, &v);
        if (!v.unit)
            continue;
        u = unit_of(units, n, v.unit);
        if (!u)
            return -1;
        if (v.display_unit && add_display(u, v.display_unit, v.display_factor))
            return -1;
    }
    return 0;
}

/* <UnitDefinitions>. */
static void write_units(FILE *f, const unit_info *units, int n)
{
    char b[32];
    int i, j;
    fprintf(f, "  <UnitDefinitions>\n");
    for (i = 0; i < n; i++) {
        fprintf(f, "    <Unit name=\"");
        put_escaped(f, units[i].name);
        fprintf(f, "\">\n      <BaseUnit");
        for (j = 0; j < NBASE; j++)
            if (units[i].exp[j])
                fprintf(f, " %s=\"%d\"", base_names[j], units[i].exp[j]);
        if (units[i].factor != 1)
            fprintf(f, " factor=\"%s\"", num(b, units[i].factor));
        fprintf(f, "/>\n");
        for (j = 0; j < units[i].ndisplay; j++) {
            fprintf(f, "      <DisplayUnit name=\"");
            put_escaped(f, units[i].display[j]);
            fprintf(f, "\" factor=\"%s\"/>\n", num(b, units[i].display_factor[j]));
        }
        fprintf(f, "    </Unit>\n");
    }
    fprintf(f, "  </UnitDefinitions>\n");
}

/* <TypeDefinitions>: the two enumerations. */
static void write_types(FILE *f)
{
    static const char *const types[2][2] = {{"Model", "parametrization of the multibody dynamics"},
                                            {"Integrator", "time integration scheme"}};
    int t, i;
    fprintf(f, "  <TypeDefinitions>\n");
    for (t = 0; t < 2; t++) {
        fprintf(f, "    <EnumerationType name=\"%s\" description=\"%s\">\n", types[t][0], types[t][1]);
        for (i = 0; i < fmu_enum_count(types[t][0]); i++)
            fprintf(f, "      <Item name=\"%s\" value=\"%d\"/>\n", fmu_enum_item(types[t][0], i), i);
        fprintf(f, "    </EnumerationType>\n");
    }
    fprintf(f, "  </TypeDefinitions>\n");
}

/* One <ModelVariables> entry. */
static void write_variable(FILE *f, unsigned vr, const fmu_var *v, double start)
{
    char b[32];
    fprintf(f, "    <%s name=\"%s\" valueReference=\"%u\" causality=\"%s\" variability=\"%s\"", type_element(v->type),
            v->name, vr, causality_name(v->causality), v->variability);
    if (v->declared_type)
        fprintf(f, " declaredType=\"%s\"", v->declared_type);
    if (v->unit) {
        fprintf(f, " unit=\"");
        put_escaped(f, v->unit);
        fprintf(f, "\"");
        if (v->display_unit) {
            fprintf(f, " displayUnit=\"");
            put_escaped(f, v->display_unit);
            fprintf(f, "\"");
        }
    }
    if (v->has_range) {
        fprintf(f, " min=\"%s\"", start_text(b, v->type, v->min));
        fprintf(f, " max=\"%s\"", start_text(b, v->type, v->max));
    }
    if (v->causality == FMU_PARAMETER || v->causality == FMU_INPUT)
        fprintf(f, " start=\"%s\"", start_text(b, v->type, start));
    fprintf(f, " description=\"");
    put_escaped(f, v->description);
    fprintf(f, "\"/>\n");
}

/* The whole modelDescription.xml; 0 or -1. */
static int write_description(FILE *f)
{
    unit_info units[MAX_UNITS];
    char token[FMU_TOKEN_LEN], b[32];
    unsigned vr, n = fmu_var_count();
    double *start = malloc(n * sizeof *start);
    int nunits;
    if (!start || fmu_vars_start(start) || fmu_vars_token(token)) {
        fprintf(stderr, "fmu-gen: out of memory\n");
        free(start);
        return -1;
    }
    if (collect_units(units, &nunits)) {
        free(start);
        return -1;
    }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(f, "<fmiModelDescription\n  fmiVersion=\"3.0\"\n  modelName=\"%s\"\n  description=\"", fmu_plant_name());
    put_escaped(f, fmu_plant_description());
    fprintf(f, "\"\n  generationTool=\"virtual Hexaglide for LinuxCNC (src/fmu/fmu_gen.c)\"\n"
               "  instantiationToken=\"%s\"\n  variableNamingConvention=\"flat\">\n\n", token);
    /* fixedInternalStepSize: the servo period, the step the board integrates by (its default: the
       parameter period sets another, and a communication step is then a multiple of that) */
    fprintf(f, "  <CoSimulation\n    modelIdentifier=\"%s\"\n    canGetAndSetFMUState=\"true\"\n"
               "    canSerializeFMUState=\"true\"\n    canHandleVariableCommunicationStepSize=\"false\"\n"
               "    fixedInternalStepSize=\"%s\"\n    hasEventMode=\"false\"/>\n\n", fmu_plant_name(),
            num(b, fmu_plant_period_default_s()));
    write_units(f, units, nunits);
    write_types(f);
    fprintf(f, "  <LogCategories>\n"
               "    <Category name=\"logStatusError\" description=\"refused calls and parameters (on unless "
               "fmi3SetDebugLogging turns it off)\"/>\n"
               "    <Category name=\"logStatusWarning\" description=\"faults of the machine, NaN volts (with loggingOn "
               "or fmi3SetDebugLogging; the step returns fmi3Warning either way)\"/>\n"
               "    <Category name=\"logEvents\" description=\"the board's other events: substeps raised, reset "
               "done (with loggingOn or fmi3SetDebugLogging)\"/>\n  </LogCategories>\n\n");
    fprintf(f, "  <DefaultExperiment startTime=\"0\" stopTime=\"1\" stepSize=\"%s\"/>\n\n",
            num(b, fmu_plant_period_default_s()));
    fprintf(f, "  <ModelVariables>\n");
    for (vr = 0; vr < n; vr++) {
        fmu_var v;
        fmu_var_get(vr, &v);
        write_variable(f, vr, &v, start[vr]);
    }
    fprintf(f, "  </ModelVariables>\n\n  <ModelStructure>\n");
    /* no output depends on an input at the same communication point (the step's outputs are of the inputs
       held from its start: one period of delay); without a dependencies list an importer must assume it
       does. The parameters are knowns too (FMI 3.0, 2.4.8): an output read from the state uses them
       (position_k = count_k / enc_scale, a switch by its threshold, the force by kt and lead), so each
       output lists every parameter, and no input */
    for (vr = 0; vr < n; vr++) {
        fmu_var v;
        unsigned p;
        const char *sep = "";
        fmu_var_get(vr, &v);
        if (v.causality != FMU_OUTPUT)
            continue;
        fprintf(f, "    <Output valueReference=\"%u\" dependencies=\"", vr);
        for (p = 0; p < n; p++) {
            fmu_var w;
            fmu_var_get(p, &w);
            if (w.causality == FMU_PARAMETER) {
                fprintf(f, "%s%u", sep, p);
                sep = " ";
            }
        }
        fprintf(f, "\"/>\n");
    }
    for (vr = 0; vr < n; vr++) {
        fmu_var v;
        fmu_var_get(vr, &v);
        if (v.causality == FMU_OUTPUT)
            fprintf(f, "    <InitialUnknown valueReference=\"%u\"/>\n", vr);
    }
    fprintf(f, "  </ModelStructure>\n\n</fmiModelDescription>\n");
    free(start);
    return 0;
}

/* v in its shortest e-form, 1e9 for 1000000000, into buf (24 bytes); its digits. */
static int md_e_form(char *buf, double v)
{
    int p, e;
    char *x;
    for (p = 1; p <= 17; p++) {
        snprintf(buf, 24, "%.*e", p - 1, v);
        if (strtod(buf, 0) == v)
            break;
    }
    x = strchr(buf, 'e');
    if (x) {
        e = atoi(x + 1);
        snprintf(x, (size_t)(24 - (x - buf)), "e%d", e);
    }
    return p;
}

/* A bound for the Markdown table: as the description writes it, 1e9 for
 * 1000000000; a strict bound, declared as the double next to a round one
 * (999999999.9999999 for below 1e9), as "below 1e9" ("above -1e9"). */
static const char *md_num(char buf[32], fmu_type t, double v)
{
    char round[24];
    if (t != FMU_FLOAT64 || fabs(v) < 1e6)
        return start_text(buf, t, v);
    if (md_e_form(buf, v) >= 16 && md_e_form(round, nextafter(v, v > 0 ? HUGE_VAL : -HUGE_VAL)) <= 3)
        snprintf(buf, 32, "%s %s", v > 0 ? "below" : "above", round);
    return buf;                        /* (else v's own e-form, written by the test) */
}

/* The variables as a Markdown table, a per-joint group in one row; 0 or -1. */
static int write_markdown(FILE *f)
{
    unsigned vr, end, n = fmu_var_count();
    double *start = malloc(n * sizeof *start);
    if (!start || fmu_vars_start(start)) {
        fprintf(stderr, "fmu-gen: out of memory\n");
        free(start);
        return -1;
    }
    fprintf(f, "| name | value reference | type | causality | unit (display unit) | start | min .. max | description |\n");
    fprintf(f, "|---|---|---|---|---|---|---|---|\n");
    for (vr = 0; vr < n; vr = end + 1) {
        char range[32], sb[32], unit[64], bounds[80], lo[32], hi[32];
        const char *cut, *st = "";
        fmu_var v;
        fmu_var_get(vr, &v);
        cut = strstr(v.description, ", joint 0 (");
        end = cut ? vr + FMU_JOINTS - 1 : vr;
        if (cut)
            snprintf(range, sizeof range, "%u..%u", vr, end);
        else
            snprintf(range, sizeof range, "%u", vr);
        if (v.causality == FMU_PARAMETER || v.causality == FMU_INPUT)
            st = v.declared_type ? fmu_enum_item(v.declared_type, (int)start[vr]) : start_text(sb, v.type, start[vr]);
        snprintf(unit, sizeof unit, "%s%s%s%s", v.unit ? v.unit : "", v.display_unit ? " (" : "",
                 v.display_unit ? v.display_unit : "", v.display_unit ? ")" : "");
        bounds[0] = 0;
        if (v.has_range)
            snprintf(bounds, sizeof bounds, "%s .. %s%s", md_num(lo, v.type, v.min), md_num(hi, v.type, v.max),
                     v.group == FMU_G_PERIOD ? ", whole ns" : v.quantum == 1 ? ", whole" : "");
        if (cut)
            v.name[strlen(v.name) - 2] = 0;  /* "dac_0" -> "dac" */
        fprintf(f, "| `%s%s` | %s | %s | %s | %s | %s | %s | %.*s |\n", v.name, cut ? "_0` .. `_5" : "", range,
                v.declared_type ? v.declared_type : type_element(v.type), causality_name(v.causality), unit, st,
                bounds, cut ? (int)(cut - v.description) : (int)strlen(v.description), v.description);
    }
    free(start);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--markdown"))
        return write_markdown(stdout) ? 1 : 0;
    if (argc != 1) {
        fprintf(stderr, "usage: fmu-gen [--markdown]  (modelDescription.xml, or the variables as Markdown, on "
                        "stdout)\n");
        return 2;
    }
    return write_description(stdout) ? 1 : 0;
}
