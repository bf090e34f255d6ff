/* hg_sensors.h - the virtual MOTENC-100 board's converters and sensors:
 * DAC and ADC conversions, quadrature encoders with index latch, limit and
 * home switches, the board watchdog. What the HAL driver
 * motenc_hexaglide_dyns_virtual puts behind hal_motenc's pins.
 *
 * Conventions: the encoder counts the motor angle in revolutions since
 * HOME, turns (the plant's, hg_plant.h: for a screw z / lead), as
 * floor(turns * counts_per_rev), so counts rise with turns and read 0 at
 * HOME after power-up; the index pulse comes once per motor revolution,
 * where turns passes a whole number (the index edge is between raw counts
 * k*cpr-1 and k*cpr). Switch positions are the plant's; the board only
 * applies stuck switches.
 *
 * Pure C and libm: no LinuxCNC dependency, no malloc, no stdio, no loops
 * that depend on data. Every function returns finite numbers for any input. */
#ifndef HG_SENSORS_H
#define HG_SENSORS_H

#include "hg_analog.h"          /* HG_DAC_VOLTS_MAX: the +-10 V DAC range */

/* The MOTENC-100's channel counts (LinuxCNC src/hal/drivers/motenc.h). */
#define HG_BOARD_ENCODERS 8
#define HG_BOARD_DACS 8
#define HG_BOARD_ADCS 8
#define HG_BOARD_INPUTS 68
#define HG_BOARD_OUTPUTS 32

/* DAC: +-10 V, 13 bits; counts = (u32)(volts * -8191/20 + 4096) as hal_motenc. */
#define HG_DAC_COUNT_ZERO 4096.0
#define HG_DAC_COUNTS_PER_VOLT (8191.0 / 20.0)
/* ADC: +-5 V, 14 bits, 16384 counts over 10 V. */
#define HG_ADC_VOLTS_MAX 5.0
#define HG_ADC_COUNTS_PER_VOLT (16384.0 / 10.0)

/* Digital inputs of channel k: limit-, limit+, home, amplifier fault, at
 * in-(4k+0..3): the layout of LinuxCNC's stock motenc_io.hal, extended
 * from 3 to 8 channels. The first three are the plant's switch bits
 * HG_SW_MIN, HG_SW_MAX, HG_SW_HOME (hg_plant.h) in this order. */
#define HG_INPUTS_PER_CHANNEL 4
enum { HG_IN_LIMIT_MIN = 0, HG_IN_LIMIT_MAX = 1, HG_IN_HOME = 2, HG_IN_AMP_FAULT = 3 };

/* Watchdog control bits (hal_motenc's watchdog-control parameter). */
#define HG_WD_CTL_16MS 0x01u
#define HG_WD_CTL_ENABLE 0x04u
#define HG_WD_CTL_AUTO_RESET 0x10u    /* reset by every dac-write */

/* Volts hal_motenc's dac-write computes: (value - offset) * gain clamped
 * to +-10 V. A NaN result counts as 0 V, +-inf clamps to +-10 V.
 * *garbage (may be 0) is set to 1 when the result was NaN, else 0. */
double hg_dac_volts(double value, double offset, double gain, int *garbage);

/* Volts the 13-bit DAC really outputs for a requested voltage in +-10 V
 * (hal_motenc's truncating count formula, converted back). */
double hg_dac_output(double volts);

/* Volts the 14-bit ADC reports for an analog input (clamped to +-5 V,
 * truncated to a count; NaN reads 0). */
double hg_adc_sample(double volts);

/* hal_motenc's adc-NN-value for sampled volts: volts * gain - offset,
 * 0 when that is not finite. */
double hg_adc_value(double volts, double gain, double offset);

/* Raw encoder count floor(turns * cpr), saturated to +-2^52 and 0 for
 * non-finite input or a non-positive cpr. */
long long hg_encoder_raw_counts(double turns, double counts_per_rev);

/* Motor revolution number floor(turns) (same saturation rules). */
long long hg_encoder_revolution(double turns);

/* One quadrature channel with its index latch: the counter hardware. */
typedef struct {
    long long raw_counts;     /* raw count of the current position */
    long long offset_counts;  /* raw count at which the counter reads 0 */
    long long revolution;     /* motor revolution of the current position */
    int latch_armed;          /* zero the counter at the next index (index-enable seen) */
    int latch_hit;            /* the armed latch fired; cleared when disarmed */
    int index_pulse;          /* an index pulse passed during the last update */
} hg_encoder;

/* Power-up at motor position turns: counter reads its raw counts, latch disarmed. */
void hg_encoder_init(hg_encoder *e, double turns, double counts_per_rev);

/* Follow the motor to turns: detect index pulses between the previous and
 * this position (unless index_lost), zero the counter at the first one if
 * the latch is armed. Returns 1 if an index pulse was seen, else 0. */
int hg_encoder_update(hg_encoder *e, double turns, double counts_per_rev, int index_lost);

/* New turns per unit of travel or counts_per_rev at motor position turns:
 * the counter keeps its reading and no index pulse is produced. */
void hg_encoder_rescale(hg_encoder *e, double turns, double counts_per_rev);

/* Arm (1) or disarm (0) the index latch; disarming clears latch_hit. */
void hg_encoder_arm(hg_encoder *e, int armed);

/* Zero the counter at the current position (hal_motenc's reset pin). */
void hg_encoder_zero(hg_encoder *e);

/* Add delta counts to the counter without motion (a glitch). */
void hg_encoder_glitch(hg_encoder *e, long long delta_counts);

/* The counter as hal_motenc's s32 count pin shows it (32-bit wrap). */
int hg_encoder_count(const hg_encoder *e);

/* Apply stuck switches: bits in stuck_mask keep their previous value. */
unsigned hg_switches_stuck(unsigned fresh, unsigned previous, unsigned stuck_mask);

/* The board watchdog: when enabled it expires unless kicked within its
 * timeout (8 ms, or 16 ms with HG_WD_CTL_16MS), and stays expired until the
 * next kick. */
typedef struct {
    unsigned control;         /* watchdog-control bits in force */
    double remaining_s;       /* time left before expiry */
    int expired;
} hg_watchdog;

/* Timeout in seconds for control bits. */
double hg_watchdog_timeout_s(unsigned control);

/* Power-up: disabled, not expired. */
void hg_watchdog_init(hg_watchdog *w);

/* New control bits; enabling (re)starts the timer. */
void hg_watchdog_set_control(hg_watchdog *w, unsigned control);

/* Restart the timer and clear an expiry (watchdog-reset pin). */
void hg_watchdog_kick(hg_watchdog *w);

/* A DAC write: kicks the watchdog when HG_WD_CTL_AUTO_RESET is set. */
void hg_watchdog_dac_write(hg_watchdog *w);

/* Let dt seconds pass; returns 1 if the watchdog is (now) expired. */
int hg_watchdog_advance(hg_watchdog *w, double dt_s);

#endif
