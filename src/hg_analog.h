/* hg_analog.h - the +-10 V analog command of servo drives: the range of
 * the MOTENC-100's DACs and of the amplifiers' command input. Pure C. */
#ifndef HG_ANALOG_H
#define HG_ANALOG_H

#define HG_DAC_VOLTS_MAX 10.0

#endif
