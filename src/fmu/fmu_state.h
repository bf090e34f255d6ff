/* fmu_state.h - the layout of an FMU state (fmu_fmi3.c): an instance's
 * block [status][values][plant] and the header of its serialized form.
 * fmu_fmi3.c owns both; the tests that forge serialized states
 * (tests/fmu/fmu_api.c, fmu_fuzz.c) read the offsets from the header. */
#ifndef FMU_STATE_H
#define FMU_STATE_H

#include <stdint.h>
#include "fmu_vars.h"

/* Modes of the FMI 3.0 co-simulation state machine this FMU has (bits). */
enum { FMU_MODE_INSTANTIATED = 1, FMU_MODE_INIT = 2, FMU_MODE_STEP = 4, FMU_MODE_TERMINATED = 8 };

/* The instance's status: the part of the FMU state besides values and plant. */
typedef struct {
    int mode;                         /* FMU_MODE_* */
    int built;                        /* the plant holds the board of the parameter values */
    double start_time;                /* of fmi3EnterInitializationMode */
    double periods;                   /* servo periods integrated since (a whole number) */
    double steps;                     /* fmi3DoStep calls that ran since (a whole number): the additions
                                         an importer keeping its time as t += h has rounded */
    double period_s;                  /* the FMU's time step: the period in whole ns as a double */
    double stop_time;                 /* fmi3EnterInitializationMode's stopTime, +inf when not defined:
                                         no step may end past it */
} fmu_status;

/* The serialized state: this header, then the block. "HGXFMU" and the
 * format's two digits open it; the token, the layout (sizes and offsets,
 * the board's layout hash) and the size must be this build's, the
 * checksum (fmu_hash) the block's; then the content is checked. */
#define FMU_SERIAL_FORMAT 3
typedef struct {
    char magic[8];                    /* "HGXFMU03" */
    char token[FMU_TOKEN_LEN];        /* the instantiation token */
    uint32_t status_bytes;            /* sizeof(fmu_status) */
    uint32_t nvars;                   /* values in the block (doubles) */
    uint64_t off_values, off_plant;   /* where values and plant start in the block */
    uint64_t plant_bytes;             /* fmu_plant_size() */
    uint64_t plant_layout;            /* fmu_plant_layout(): the board's field layout */
    uint64_t size;                    /* bytes of the block */
    uint64_t checksum;                /* fmu_hash of the block */
} fmu_serial_header;

#endif
