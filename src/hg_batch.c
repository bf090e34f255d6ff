/* hg_batch.c - independent hg_loop runs spread over POSIX threads. */
#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>
#include "hg_batch.h"
#include "hg_errors.h"

#define BATCH_THREADS_MAX 256

/* What every worker shares: the jobs, the results, the next job's index. */
typedef struct {
    const hg_batch_job *jobs;
    hg_batch_result *res;
    long njobs;
    long next;
    pthread_mutex_t lock;
} batch;

typedef struct {
    batch *b;
    hg_loop *L;                        /* this worker's loop */
} worker;

int hg_batch_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n >= 1 ? (n > BATCH_THREADS_MAX ? BATCH_THREADS_MAX : (int)n) : 1;
}

/* The next job's index, or -1 when none is left. */
static long take(batch *b)
{
    long i;
    pthread_mutex_lock(&b->lock);
    i = b->next < b->njobs ? b->next++ : -1;
    pthread_mutex_unlock(&b->lock);
    return i;
}

/* One job, from HOME at rest, on the worker's loop. */
static void run_job(hg_loop *L, const hg_batch_job *j, hg_batch_result *r)
{
    r->stop_bound = -1.0;
    r->rc = hg_loop_init(L, j->cfg, j->params);
    if (r->rc) {
        r->sum = (hg_loop_summary){0};
        r->sum.tripped_at = -1;
        return;
    }
    L->board.skip_tool_error = j->skip_tool_error;
    r->rc = hg_loop_run_stop(L, j->cmd_mm, j->n, j->from, &j->trace, j->stop, &r->sum, &r->stop_bound);
}

/* A worker: jobs until none is left. */
static void *work(void *arg)
{
    worker *w = arg;
    long i;
    while ((i = take(w->b)) >= 0)
        run_job(w->L, &w->b->jobs[i], &w->b->res[i]);
    return 0;
}

int hg_batch_run(const hg_batch_job *jobs, long njobs, int threads, hg_batch_result *res)
{
    batch b;
    worker w[BATCH_THREADS_MAX];
    pthread_t tid[BATCH_THREADS_MAX];
    int started[BATCH_THREADS_MAX] = {0};
    int t, n;
    if (njobs < 0 || (njobs > 0 && (!jobs || !res)))
        return HG_ERR_BAD_PARAM;
    if (njobs == 0)
        return 0;
    n = threads > 0 ? threads : hg_batch_cores();
    if (n > BATCH_THREADS_MAX)
        n = BATCH_THREADS_MAX;
    if (n > njobs)
        n = (int)njobs;
    b = (batch){jobs, res, njobs, 0, PTHREAD_MUTEX_INITIALIZER};
    for (t = 0; t < n; t++) {
        w[t].b = &b;
        w[t].L = malloc(sizeof(hg_loop));
        if (!w[t].L)
            break;
    }
    if (t == 0)
        return HG_ERR_NO_MEMORY;
    n = t;                             /* as many workers as loops */
    for (t = 1; t < n; t++)
        started[t] = pthread_create(&tid[t], 0, work, &w[t]) == 0;
    work(&w[0]);                       /* the caller's thread works too */
    for (t = 1; t < n; t++)
        if (started[t])
            pthread_join(tid[t], 0);
    for (t = 0; t < n; t++)
        free(w[t].L);
    pthread_mutex_destroy(&b.lock);
    return 0;
}

unsigned long hg_batch_sizeof(int which)
{
    return which == 0 ? sizeof(hg_batch_job) : which == 1 ? sizeof(hg_batch_result) : 0;
}
