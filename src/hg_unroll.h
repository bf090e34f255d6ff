/* hg_unroll.h - HG_UNROLL before a loop with a fixed trip count asks GCC to
 * unroll it by six: completely for the 6-long loops over the 6x6 blocks of
 * the dynamics, in chunks of six for longer ones. */
#ifndef HG_UNROLL_H
#define HG_UNROLL_H

#define HG_UNROLL _Pragma("GCC unroll 6")

#endif
