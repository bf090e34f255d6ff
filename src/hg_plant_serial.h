/* hg_plant_serial.h - a serial-axis machine (a mill, a router, a lathe,
 * a rotary table: one drive per axis, LinuxCNC's trivkins) as a plant of
 * the virtual board (hg_plant.h): 1 to 8 independent axes, one per
 * DAC/encoder channel, each a load on a drive train behind a servo motor
 * and amplifier, with gravity, a counterbalance, viscous, sliding and
 * breakaway friction, hard stops, limit and home switches and an encoder
 * with its index once per motor revolution. docs/serial.md.
 *
 * The model variant is the axes string (model=XYZ): one letter per
 * channel, XYZUVW linear (m, N; mm on HAL), ABC rotary (rad, N m; deg on
 * HAL). Its parameter table has one block of entries per axis N: spec
 * name "<field>_N", HAL name "joint-N.<field>", INI key "<FIELD>_N" of
 * [SERIAL] (value in the HAL unit). Positions are the plant's own: 0 is
 * where the machine stands after power-up or a reset, a motor angle of 0
 * (an index mark); the encoder counts from there. */
#ifndef HG_PLANT_SERIAL_H
#define HG_PLANT_SERIAL_H

#include "hg_plant.h"

extern const hg_plant hg_plant_serial;

/* A rotary axis this far beyond its hard stop (rad) has gone through it
 * (a linear one: HG_THROUGH_STOP_M, hg_stop.h). */
#define HG_SERIAL_THROUGH_STOP_RAD 0.0872664625997164788 /* 5 deg */

/* The axes' fields, in the order of each axis's block of the table (a
 * rotary axis has no G and no COUNTERBALANCE entry). */
enum {
    HG_SF_MASS = 0, HG_SF_G, HG_SF_COUNTERBALANCE, HG_SF_LEAD, HG_SF_J_ROTOR, HG_SF_KT, HG_SF_R_WINDING,
    HG_SF_L_WINDING, HG_SF_AMP_MODE, HG_SF_KA, HG_SF_I_MAX, HG_SF_V_BUS, HG_SF_V_RATED, HG_SF_KP_VEL,
    HG_SF_KI_VEL, HG_SF_K_AXIAL, HG_SF_C_AXIAL, HG_SF_BACKLASH, HG_SF_C_VISC, HG_SF_F_COULOMB,
    HG_SF_F_STATIC, HG_SF_V_STRIBECK, HG_SF_STOP_MIN, HG_SF_STOP_MAX, HG_SF_K_STOP, HG_SF_C_STOP,
    HG_SF_LIMIT_MIN, HG_SF_LIMIT_MAX, HG_SF_HOME_SWITCH, HG_SF_COUNTS_PER_REV, HG_SF_COUNT
};

/* Table entry of field f of axis `axis` in variant, or -1 (no such axis,
 * or a field a rotary axis lacks). */
int hg_serial_entry(int variant, int axis, int field);

/* Energies of the machine in d (J): kinetic (loads and rotors), potential
 * (gravity less the counterbalance, from the power-up position, and the
 * drive trains' springs). */
void hg_serial_energy(const hg_plant_model *m, const hg_plant_data *d, double *kinetic_j, double *potential_j);

#endif
