/* fmu_plant.h - the FMU's one door to the board core: the adapter.
 * fmu_plant.c is the only file of src/fmu/ that includes hg_board.h or
 * hg_plant.h (the board and its plant registry); the FMI glue (fmu_fmi3.c), the variable table (fmu_vars.c)
 * and the modelDescription.xml generator (fmu_gen.c) see the machine only
 * through this header: its parameters (name, SI unit, default,
 * description, display unit), its parametrizations and integrators, one
 * servo period of the board, and the core's messages.
 *
 * A plant is fmu_plant_size() bytes without pointers (the board core
 * keeps no pointers), so a byte copy is a complete snapshot of it (the
 * FMU state functions copy it); it begins with the core's hg_board (the
 * tests that forge states find the board's fields there). Units: SI and
 * radians. No file-scope mutable state: two plants never share anything. */
#ifndef FMU_PLANT_H
#define FMU_PLANT_H

#include <stddef.h>

#define FMU_JOINTS 6                  /* DAC channels, encoders, carriages */

/* One period's inputs: what a controller (or LinuxCNC) drives. */
typedef struct {
    double dac_v[FMU_JOINTS];         /* DAC command volts (the board clamps to +-10 V; NaN outputs 0 V) */
    int estop;                        /* the E-STOP button is pressed */
    int reset;                        /* the board's reset (a rising edge clears a fault, machine to HOME) */
    int amp_enable;                   /* the digital output in the E-STOP loop (out-07, LinuxCNC's
                                         iocontrol.0.user-enable-out): amplifiers powered when TRUE */
} fmu_plant_inputs;

/* One period's outputs (all finite). */
typedef struct {
    int count[FMU_JOINTS];            /* encoder counts */
    double position[FMU_JOINTS];      /* count / enc_scale */
    int index[FMU_JOINTS];            /* an index pulse passed */
    int limit_min[FMU_JOINTS], limit_max[FMU_JOINTS], home[FMU_JOINTS]; /* switches */
    int fault, fault_code, amps_on;   /* fault latched, its code (0 none), amplifiers on */
    double z_m[FMU_JOINTS], zd_mps[FMU_JOINTS]; /* carriage heights from HOME and velocities */
    double pose[6];                   /* head X Y Z (m), A B C (rad) */
    double current_a[FMU_JOINTS];     /* winding currents */
    double force_n[FMU_JOINTS];       /* drive forces on the carriages */
} fmu_plant_outputs;

/* One model parameter, from the core's parameter table. */
typedef struct {
    const char *name;                 /* spec name, e.g. "m_head" */
    const char *unit;                 /* SI unit ("1": none) */
    const char *description;
    const char *display_unit;         /* the unit LinuxCNC shows it in ("mm"), or the SI unit */
    double display_factor;            /* display value = SI value * display_factor */
    double start;                     /* the default (SI) */
    double min, max;                  /* the bounds of its rules on itself alone (inclusive, SI):
                                         outside them the core refuses it whatever the others are */
    double quantum;                   /* > 0: the core takes only whole multiples of it (amp_mode 0 or 1) */
} fmu_param;

/* What the FMU asks the core to build. */
typedef struct {
    long long model;                  /* parametrization, 0..fmu_plant_model_count()-1 */
    long long integrator;             /* 0..fmu_plant_integrator_count()-1 */
    long long substeps;               /* integration steps per servo period */
    double period_s;                  /* the servo period, whole nanoseconds */
    double enc_scale;                 /* encoder counts per position unit */
    const double *params;             /* fmu_plant_param_count() values, SI */
} fmu_plant_setup;

/* How grave a message is (the FMI glue maps it to an fmi3Status). */
enum { FMU_SAY_INFO = 0, FMU_SAY_WARNING = 1, FMU_SAY_ERROR = 3 };

/* The sink of the core's messages (level FMU_SAY_*, one sentence). */
typedef void fmu_say_fn(void *env, int level, const char *text);

/* Name of the plant ("hexaglide": the FMU's model identifier) and one line about it. */
const char *fmu_plant_name(void);
const char *fmu_plant_description(void);

/* Bytes of one plant (malloc them; no alignment beyond malloc's needed). */
size_t fmu_plant_size(void);

/* The model parameters: count, and entry i (0 <= i < count) into *p (0, or -1 for another i). */
int fmu_plant_param_count(void);
int fmu_plant_param(int i, fmu_param *p);

/* The core's reason for refusing value x of model parameter i with the
 * others at params[] (fmu_plant_param_count() values), or 0 when it takes
 * entry i so. */
const char *fmu_plant_param_why(int i, const double *params, double x);

/* Parametrizations and integrators: count, name of i (0 for another i), default. */
int fmu_plant_model_count(void);
const char *fmu_plant_model_name(int i);
int fmu_plant_model_default(void);
int fmu_plant_integrator_count(void);
const char *fmu_plant_integrator_name(int i);

/* The board's load-time substeps, integrator and encoder scale, as the
 * core sets them: 0, or -1 (out of memory). */
int fmu_plant_defaults(long long *substeps, long long *integrator, double *enc_scale);

/* The most substeps the board takes. */
long long fmu_plant_substeps_max(void);

/* Servo period (s): the default, the shortest and the longest the board integrates. */
double fmu_plant_period_default_s(void);
double fmu_plant_period_min_s(void);
double fmu_plant_period_max_s(void);

/* The rule of a servo period: 0 for a whole number of nanoseconds in
 * [min, max] (within 1e-6 ns: the rounding of the double), else -1 with
 * the rule, naming the nearest whole-ns values, in why (len bytes). */
int fmu_plant_period_why(double period_s, char *why, size_t len);

/* The period a value that passes fmu_plant_period_why puts in force: its
 * whole nanoseconds / 1e9 (the double nearest to them; 0.001 for 0.001). */
double fmu_plant_period_in_force_s(double period_s);

/* The rule of an encoder scale: 0 when finite and at least HG_ENC_SCALE_MIN
 * in magnitude (the board's), else -1 with the rule in why. */
int fmu_plant_enc_scale_why(double enc_scale, char *why, size_t len);

/* Build the board of s at HOME at rest, as the HAL component refuses or
 * loads it: 0, or -1 after one FMU_SAY_ERROR message per refused value
 * (its name, value and the rule) through say. */
int fmu_plant_init(void *plant, const fmu_plant_setup *s, fmu_say_fn *say, void *env);

/* The servo period the board integrates: its whole ns as the nearest
 * double (ns / 1e9: the double an importer reads "0.001" as). */
double fmu_plant_period_s(const void *plant);

/* Check plant bytes of unknown origin (a deserialized FMU state): 0 when
 * they can be a plant fmu_plant_init built of s and fmu_plant_step
 * stepped (the model is the core's build of s bit for bit, indices and
 * counters in range, the sensors what the plant shows of its state),
 * else -1 with the first thing wrong in why (len bytes). */
int fmu_plant_check(const void *plant, const fmu_plant_setup *s, char *why, size_t len);

/* Empty the caches of plant bytes that fmu_plant_check passed
 * (hg_board_forget): what they hold was not checked. */
void fmu_plant_forget(void *plant);

/* A hash of the plant's layout (sizes and offsets of the board's fields):
 * the serialized FMU state's header carries it. */
unsigned long long fmu_plant_layout(void);

/* Outputs of the board as it stands, without stepping. */
void fmu_plant_peek(const void *plant, fmu_plant_outputs *o);

/* One servo period with inputs in, from the FMU's time t_s: the outputs,
 * and the core's events through say (a latched fault, naming the period
 * by the FMU's time, NaN volts: FMU_SAY_WARNING; more substeps than asked:
 * FMU_SAY_INFO). Returns the gravest level said. */
int fmu_plant_step(void *plant, const fmu_plant_inputs *in, double t_s, fmu_plant_outputs *o, fmu_say_fn *say,
                   void *env);

#endif
