/* hg_plant.h - the one narrow interface between the virtual board and the
 * machine behind it (the plant): its parameters, its state, one step from
 * the drive commands, and what its sensors read. The board (hg_board.h:
 * DACs, encoders with index, switches as digital inputs, ADCs, watchdog,
 * E-STOP, fault latch, substeps with rollback, record and replay) knows no
 * plant's facts; every plant (the Hexaglide, hg_plant_hexaglide.c; a
 * serial-axis machine, hg_plant_serial.c) knows nothing of the board.
 *
 * A plant is a table of functions and facts (hg_plant), found by name in
 * the registry (hg_plants.c). Its parameters are a block of doubles in SI
 * units, entry i being entry i of its parameter table (hg_param_table.h:
 * name, unit, HAL name and scale, INI key). Its model (constant after
 * build) and data (mutable state, then scratch) live in storage the
 * caller owns (hg_plant_model, hg_plant_data): plain structs, no
 * pointers, so a board can live in hal_malloc'd memory; each plant checks
 * at compile time that its types fit.
 *
 * Channels: the plant uses DAC/encoder/ADC channels 0..channels-1 and the
 * digital inputs of those channels (HG_INPUTS_PER_CHANNEL each). Units:
 * SI inside; a channel is linear (m, N) or rotary (rad, N m).
 *
 * Pure C, no LinuxCNC include, no malloc, no stdio. */
#ifndef HG_PLANT_H
#define HG_PLANT_H

#include "hg_param_table.h"

#define HG_CHANNELS_MAX 8            /* the MOTENC-100's DAC, encoder and ADC channels */
#define HG_PLANT_PARAMS_MAX 256      /* entries of a plant's parameter block */
#define HG_PLANT_EXTRA_MAX 16        /* plant-specific outputs (head pose, ...) */
#define HG_PLANT_INJECT_MAX 4        /* plant-specific fault injections per channel */
#define HG_PLANT_MODEL_DOUBLES 768   /* storage of a plant's model (doubles) */
#define HG_PLANT_DATA_DOUBLES 2048   /* storage of a plant's data: state, then scratch (doubles) */
#define HG_PLANT_TEXT_LEN 240        /* a plant's sentences (fault descriptions) */

/* Switch bits of one channel (the digital inputs limit-, limit+, home). */
enum { HG_SW_MIN = 1u << 0, HG_SW_MAX = 1u << 1, HG_SW_HOME = 1u << 2 };

/* A parameter block: entry i of the plant's table at v[i], SI units. */
typedef struct {
    double v[HG_PLANT_PARAMS_MAX];
} hg_plant_params;

/* Storage of a plant's model and data (each plant lays its own types over them). */
typedef struct {
    double store[HG_PLANT_MODEL_DOUBLES];
} hg_plant_model;
typedef struct {
    double store[HG_PLANT_DATA_DOUBLES];
} hg_plant_data;

/* What a failed step struck or crossed (the plant describes it as text). */
typedef struct {
    int kind;                        /* plant-specific, 0: nothing */
    int channel, other;              /* the channel(s) or bar(s) involved, -1 if none */
    double value, limit;             /* what was found and the limit crossed (SI) */
} hg_plant_report;

/* What the plant's sensors and state show after a step (all finite). */
typedef struct {
    int channels;                    /* channels in use (the rest read 0) */
    unsigned rotary;                 /* bit ch: channel ch is rotary (rad, N m), else linear (m, N) */
    double turns[HG_CHANNELS_MAX];   /* encoder side: motor revolutions since HOME (the encoder
                                        counts turns * counts_per_rev, indexes at whole turns) */
    double counts_per_rev[HG_CHANNELS_MAX]; /* the motor encoder's counts per revolution */
    double turns_per_unit[HG_CHANNELS_MAX]; /* motor revolutions per SI unit (m, rad) of motor_pos, signed as
                                        turns counts: the encoder's counts per unit are
                                        counts_per_rev * turns_per_unit */
    double motor_pos[HG_CHANNELS_MAX]; /* encoder side as a load position (m or rad) */
    double pos[HG_CHANNELS_MAX];     /* load side: carriage or axis position (m or rad) */
    double vel[HG_CHANNELS_MAX];     /* its velocity */
    double current_a[HG_CHANNELS_MAX]; /* winding current */
    double force[HG_CHANNELS_MAX];   /* net non-inertial force on the load (N or N m) */
    unsigned switches[HG_CHANNELS_MAX]; /* HG_SW_* the load's position trips */
    double extra[HG_PLANT_EXTRA_MAX]; /* the plant's own outputs, as its extra table says (SI) */
    double sim_time_s;
} hg_plant_sense;

/* One plant-specific output (a HAL pin motenc-hexaglide.<board>.<hal_name>). */
typedef struct {
    const char *hal_name;            /* e.g. "head-x" */
    const char *unit;                /* HAL unit, e.g. "mm" */
    double hal_scale;                /* HAL value = SI value * hal_scale */
    int is_u32;                      /* 1: shown as a u32 pin (a count, a fingerprint), else float */
    const char *rec_name;            /* record column out.<rec_name> (replay compares it), or 0 */
    const char *csv_name;            /* its column in `hexaglide sim`'s CSV (unit in the name), or 0 */
    const char *what;                /* one line */
} hg_plant_output;

/* One plant-specific fault injection per channel (HAL pin
 * motenc-hexaglide.<board>.joint-N.<hal_name>). */
typedef struct {
    const char *hal_name;            /* e.g. "bar-broken" */
    int blocks_reset;                /* 1: a reset is refused while it is set (it cannot be undone) */
    const char *what;                /* what it does, for the message when it acts */
} hg_plant_injection;

/* Classes of a parameter change (hg_plant.change). */
enum {
    HG_PLANT_CHANGE_RESTART = 1u << 0, /* the machine's shape changed: restart at HOME */
    HG_PLANT_CHANGE_RESCALE = 1u << 1, /* the encoders' turns per unit of travel changed */
    HG_PLANT_CHANGE_ROUNDING = 1u << 2 /* with RESTART: the shape moved by rounding only (every field
                                          within 4 ulps, a value shown in mm typed back: 68.254 / 1000
                                          is 1 ulp off 0.068254); the state the machine is in stays valid */
};

/* Everything the board needs of a plant. The model variant (the
 * Hexaglide's parametrization; a serial machine's axes, "XYZC") is fixed
 * at load: the parameter table, the channels in use and their units may
 * depend on it. */
typedef struct {
    const char *name;                /* "hexaglide" */
    const char *what;                /* one line */
    const char *ini_section;         /* the INI section of its parameters ("HEXAGLIDE") */
    const char *ini_hal_file;        /* the shipped HAL file that reads every key of that section (halcmd
                                        stops at the first missing one), 0 if a config's own HAL file
                                        reads what it needs and a missing key keeps its default */
    const char *ini_hal_pins;        /* what ini_hal_file sets from a key: a format with the parameter's
                                        HAL name twice ("hexaglidekins.%s and motenc-hexaglide.0.%s") */
    const char *variants_help;       /* what model= takes, for messages */
    int default_variant;             /* the variant a board loads without being told */
    const hg_plant_output *outputs;  /* its extra outputs (sense.extra[i]) */
    int noutputs;
    const hg_plant_injection *injections; /* its per-channel fault injections (bit i of inject[ch]) */
    int ninjections;
    unsigned long model_bytes, data_bytes; /* sizes of its model and data types (<= the storage) */
    unsigned long state_bytes;       /* the first state_bytes of its data are its whole state; the rest
                                        is scratch, whose caches are empty when it is all zeros */
    /* the variant called name (model=), or -1 */
    int (*variant_of)(const char *name);
    /* its name into buf (len bytes): 0, or -1 for no such variant */
    int (*variant_name)(int variant, char *buf, int len);
    /* channels in use (1..HG_CHANNELS_MAX): HAL exports joint-0 .. joint-(n-1) */
    int (*channels)(int variant);
    /* entries of its parameter table, and entry i (units as the variant
     * has them: a rotary axis's positions in rad, deg on HAL): 0 or -1 */
    int (*nparams)(int variant);
    int (*param)(int variant, int i, hg_param_info *out);
    /* the spec's defaults into v */
    void (*defaults)(int variant, hg_plant_params *v);
    /* into v (the defaults): the parameters a record of an earlier format
     * (hg_board_rec.h) does not carry, as the version that wrote it had
     * them (the Hexaglide's format 1: a rigid drive train) */
    void (*legacy)(int format, int variant, hg_plant_params *v);
    /* check v: 0, or HG_ERR_BAD_PARAM with every invalid entry's bit set in
     * *bad and, if why is given, why[i] its reason (static strings) */
    int (*check)(int variant, const hg_plant_params *v, hg_bitset *bad, const char *why[HG_PLANT_PARAMS_MAX]);
    /* build the model: 0, or a code with *field, *why naming the cause */
    int (*build)(hg_plant_model *m, const hg_plant_params *v, int variant, int integrator,
                 const char **field, const char **why);
    /* the parameter block of a built model */
    void (*params_of)(const hg_plant_model *m, hg_plant_params *v);
    /* HOME at rest: 0 or a code */
    int (*reset)(const hg_plant_model *m, hg_plant_data *d);
    /* a change from parameters a to b: HG_PLANT_CHANGE_* bits */
    unsigned (*change)(int variant, const hg_plant_params *a, const hg_plant_params *b);
    /* how many steps of one period the scheme needs to integrate v stably
     * (substeps_min..substeps_max): 0 and *substeps, or HG_ERR_STIFF; both
     * name the limiting table entry (*param, -1 if none) and its longest
     * stable step *dt_max_s */
    int (*stability)(int variant, const hg_plant_params *v, int integrator, double period_s,
                     unsigned substeps_min, unsigned substeps_max, unsigned *substeps, int *param,
                     double *dt_max_s);
    /* apply injections inject[ch] (bits of the injection table) before a
     * step; returns per injection entry i a mask of the channels it newly
     * acted on in acted[i] */
    void (*inject)(const hg_plant_model *m, hg_plant_data *d, const unsigned inject[HG_CHANNELS_MAX],
                   unsigned acted[HG_PLANT_INJECT_MAX]);
    /* one step of dt with drive commands volts[ch] (DAC volts; the amplifier
     * of channel ch is on when bit ch of enabled is set): 0, or a code
     * (the caller restores the state it saved) with *r (may be 0) naming
     * what was struck */
    int (*step)(const hg_plant_model *m, hg_plant_data *d, const double volts[HG_CHANNELS_MAX],
                unsigned enabled, double dt_s, hg_plant_report *r);
    /* what the sensors show */
    void (*sense)(const hg_plant_model *m, const hg_plant_data *d, hg_plant_sense *s);
    /* the tool-path error (m): the distance of the tool from where the
     * commanded load positions pos_cmd[ch] (SI) put it; -1 when they put
     * it nowhere the plant can find (no pose near the present one) */
    double (*tool_error)(const hg_plant_model *m, const hg_plant_data *d, const double pos_cmd[HG_CHANNELS_MAX]);
    /* a report as one sentence (names its parameter by HAL name when hal is 1) */
    void (*describe)(const hg_plant_report *r, int hal, char buf[HG_PLANT_TEXT_LEN]);
} hg_plant;

/* The registry (hg_plants.c): plant i (0 the Hexaglide, the default), 0
 * past the last; the index of the plant called name, or -1. Indices are
 * stable: records name their plant by it. */
const hg_plant *hg_plant_at(int i);
int hg_plant_find(const char *name);

/* Add plant p to the registry after the built-in plants (a plant of a
 * program's own: a test's, an application's): its index, or -1 (a null
 * plant or name, a name taken, storage too small for its model or data,
 * or HG_PLANTS_ADDED_MAX added already). Not thread-safe; call before any
 * board uses the index. The index of an added plant is the program's
 * own: records naming it replay only where the same plant is added. */
#define HG_PLANTS_ADDED_MAX 4
int hg_plant_register(const hg_plant *p);

/* Variant called name of plant p (its default for a null name), or -1. */
int hg_plant_variant(const hg_plant *p, const char *name);

/* Entry i of plant p's table with model variant v (units as the variant
 * has them) into *out: 0, or -1 past the table. */
int hg_plant_param(const hg_plant *p, int variant, int i, hg_param_info *out);

/* Index of the entry called name, or -1. */
int hg_plant_param_find(const hg_plant *p, int variant, const char *name);

/* The same by registry index, for bindings that cannot follow the struct
 * (Python): the number of entries (0 for an unknown plant or variant),
 * the channels it uses (0 for an unknown plant or variant),
 * entry i (0 or -1), the defaults (0 or -1), the name (0 if unknown) and
 * the variant called name (-1 if unknown); the INI section of its parameters (0 if unknown). */
int hg_plant_nparams_at(int plant, int variant);
int hg_plant_channels_at(int plant, int variant);
int hg_plant_param_at(int plant, int variant, int i, hg_param_info *out);
int hg_plant_defaults_at(int plant, int variant, hg_plant_params *v);
const char *hg_plant_name_at(int plant);
const char *hg_plant_ini_section_at(int plant);
int hg_plant_variant_named(int plant, const char *name);

/* Switch bits (HG_SW_*) of a load at pos with limit switches at limit_min
 * (tripped at or below) and limit_max (at or above) and a home switch on
 * at or above home_at; a non-finite pos trips both limits. */
unsigned hg_plant_switches(double pos, double limit_min, double limit_max, double home_at);

#endif
