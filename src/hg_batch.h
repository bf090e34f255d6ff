/* hg_batch.h - many independent closed-loop runs (hg_loop) at once, over
 * every core: a batch of jobs (a config with gains, the board's parameters,
 * joint commands), each run from HOME at rest by hg_loop_init +
 * hg_loop_run_traced on a loop of its own, POSIX threads taking the next
 * job until none is left. The results are what serial runs give, bit for
 * bit, whatever the number of threads (the jobs share nothing but read-only
 * inputs; tests/unit/test_batch.c). For `hexaglide tune` (candidate gains x
 * jittered starts), and soak, replay's what-ifs or identify's runs through
 * the binding (tools/hexaglide.py: hg.batch).
 * Host only (threads, malloc): not in the realtime modules. */
#ifndef HG_BATCH_H
#define HG_BATCH_H

#include "hg_loop.h"

/* One run: inputs are read only (jobs may share them), traces written. */
typedef struct {
    const hg_loop_config *cfg;         /* gains, scales, biquads, trip limit, period, plant */
    const hg_board_params *params;     /* the board's parameters (0: the plant's defaults) */
    const double *cmd_mm;              /* n x joints joint commands (row-major) */
    long n;                            /* periods */
    long from;                         /* the summary counts periods from here on */
    hg_loop_trace trace;               /* per-period traces, n x joints each (0: not kept) */
    int skip_tool_error;               /* 1: the run skips the tool-path error (the plant's forward
                                          solve; a search that reads only f-errors): the summary's
                                          peak_tool_error_mm is HG_TOOL_ERROR_SKIPPED, the rest the same bits */
    const hg_loop_stop *stop;          /* the run's early stop (hg_loop_run_stop), 0: none */
} hg_batch_job;

/* One run's outcome. */
typedef struct {
    hg_loop_summary sum;               /* as hg_loop_run's */
    int rc;                            /* hg_loop_init's code, or the run's (0 ok; a fault) */
    double stop_bound;                 /* the job's stop: the bound that stopped the run, -1 if none did */
} hg_batch_result;

/* The online processors (at least 1): the default thread count. */
int hg_batch_cores(void);

/* Run jobs[0..njobs) on `threads` threads (<= 0: hg_batch_cores(); never
 * more than njobs; the caller's thread is one of them), results in
 * res[0..njobs). 0; HG_ERR_BAD_PARAM for njobs < 0 or a null pointer;
 * HG_ERR_NO_MEMORY when no loop could be allocated (nothing run). A thread
 * that cannot be started leaves its share to the others. */
int hg_batch_run(const hg_batch_job *jobs, long njobs, int threads, hg_batch_result *res);

/* sizeof the structs, for bindings that mirror them: 0 hg_batch_job, 1 hg_batch_result; else 0. */
unsigned long hg_batch_sizeof(int which);

#endif
