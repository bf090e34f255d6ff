/* test_golden.c - the dynamics step gives today what earlier commits gave.
 *
 * Two golden sets, each a file of the states hg_step reached at
 * checkpoints of a set of scenarios, written as hexadecimal floats by this
 * very program built against the commit the file names:
 *  - tests/data/golden-d20d9e5.txt: commit d20d9e5 (the version before the
 *    step was made cheaper, before the plant interface and the flexible
 *    drive train), every scenario on the rigid train (k_axial = 0) with one
 *    step per 1 ms period;
 *  - tests/data/golden-7829bca-flexible.txt: commit 7829bca (before the
 *    guard's bounds of issue 23's second round), the default flexible
 *    trains with the substeps the board runs them at (5 Heun, 2 RK4, 19
 *    improved Euler steps a period, volts held over the period), rotors
 *    included in the state.
 * The independent fact is those earlier builds' output: every later change
 * that claims to keep the answers (an optimization, the rigid limit
 * k_axial = 0 of the drive train, a refactoring) must give the same
 * numbers. The scenarios cover every model kind and scheme, stick and
 * slip, the frictionless fused step, velocity-mode amplifiers, a
 * bus-limited dash, the drives off (a sink), a hard stop, a broken bar
 * and (flexible) backlash; each step's failure code and the stuck
 * carriages are compared too.
 *
 * Asserted per scenario: the same steps fail with the same codes, the
 * same carriages stick at every checkpoint, positions within 1e-12 m (and
 * rad), velocities within 1e-9 m/s (rad/s), currents within 1e-9 A; the
 * number of checkpoints that are bit-identical is reported.
 *   test_golden --write SET FILE   writes set SET's file (0: d20d9e5, 1:
 *                                  flexible; done once, at its commit) */
#include <stdlib.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_units.h"

#define STEPS 1200
#define EVERY 100
#define NSTATE_RIGID 30      /* z, zd, pose, posed, current */
#define NSTATE 42            /* ... and (flexible) the rotors' zr, zrd */

typedef struct {
    const char *name;
    int kind, integrator;
    int frictionless, velocity_mode;
    int motion;              /* 0 servo sines, 1 drives off (sink), 2 full volts up, 3 into the top stop */
    unsigned broken;         /* bars broken at step 200 */
    double backlash_m;       /* flexible set: the trains' backlash */
} scenario;

static const scenario scenarios[] = {
    {"standard heun servo", HG_MODEL_STANDARD, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"standard euler servo", HG_MODEL_STANDARD, HG_INTEGRATOR_IMPROVED_EULER, 0, 0, 0, 0, 0.0},
    {"joints heun servo", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"joints rk4 servo", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_RK4, 0, 0, 0, 0, 0.0},
    {"cartesian heun servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"cartesian euler servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 0, 0, 0, 0, 0.0},
    {"cartesian rk4 servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_RK4, 0, 0, 0, 0, 0.0},
    {"fused heun servo", HG_MODEL_FUSED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"fused euler frictionless", HG_MODEL_FUSED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 1, 0, 0, 0, 0.0},
    {"cartesian euler frictionless", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 1, 0, 0, 0, 0.0},
    {"cartesian heun velocity mode", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 1, 0, 0, 0.0},
    {"cartesian heun sink", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 1, 0, 0.0},
    {"joints heun sink", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_HEUN, 0, 0, 1, 0, 0.0},
    {"cartesian heun full volts", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 2, 0, 0.0},
    {"cartesian heun top stop", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 3, 0, 0.0},
    {"cartesian heun bar 2 broken", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 1u << 2, 0.0},
    {"standard heun bar 0 broken", HG_MODEL_STANDARD, HG_INTEGRATOR_HEUN, 0, 0, 0, 1u << 0, 0.0},
};

/* The flexible set: the default trains, every kind and scheme once. */
static const scenario flexible_scenarios[] = {
    {"flexible cartesian heun servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"flexible cartesian heun servo, backlash 20 um", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 20e-6},
    {"flexible cartesian rk4 servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_RK4, 0, 0, 0, 0, 0.0},
    {"flexible cartesian euler servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 0, 0, 0, 0, 0.0},
    {"flexible joints heun servo", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"flexible standard heun servo", HG_MODEL_STANDARD, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"flexible fused heun servo", HG_MODEL_FUSED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0, 0.0},
    {"flexible cartesian heun velocity mode", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 1, 0, 0, 0.0},
    {"flexible cartesian heun sink", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 1, 0, 0.0},
    {"flexible cartesian heun full volts", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 2, 0, 0.0},
    {"flexible cartesian heun top stop", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 3, 0, 0.0},
    {"flexible cartesian heun bar 2 broken", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 1u << 2, 0.0},
};

/* A golden set: its file, the commit that wrote it, its scenarios, flexible or rigid trains. */
typedef struct {
    const char *path, *commit;
    const scenario *sc;
    int n, flexible, nstate;
} golden_set;

static const golden_set sets[] = {
    {"tests/data/golden-d20d9e5.txt", "d20d9e5", scenarios, (int)(sizeof scenarios / sizeof scenarios[0]), 0,
     NSTATE_RIGID},
    {"tests/data/golden-7829bca-flexible.txt", "7829bca", flexible_scenarios,
     (int)(sizeof flexible_scenarios / sizeof flexible_scenarios[0]), 1, NSTATE},
};
#define NSETS ((int)(sizeof sets / sizeof sets[0]))
#define NSCEN_MAX 17
typedef char golden_sets_fit[(sizeof scenarios / sizeof scenarios[0] <= NSCEN_MAX &&
                              sizeof flexible_scenarios / sizeof flexible_scenarios[0] <= NSCEN_MAX) ? 1 : -1];

/* The substeps the board runs the default flexible trains at in a 1 ms
 * period with this scheme (the stability check's, docs/model.md). */
static int flexible_substeps(int integrator)
{
    return integrator == HG_INTEGRATOR_RK4 ? 2 : integrator == HG_INTEGRATOR_HEUN ? 5 : 19;
}

/* One checkpoint: step index, the step's code, stuck carriages, the state. */
typedef struct {
    int step, rc;
    unsigned stuck;
    double x[NSTATE];
} checkpoint;

/* DAC volts of scenario s at step i for the state in d (hold + P on sines). */
static void volts_of(const scenario *s, const hg_model *m, const hg_data *d, int i, double v[6])
{
    const hg_params *p = &m->p;
    const double hold = p->g_mps2 * (p->m_head_kg + 6.0 * (p->m_bar_kg + p->m_carriage_kg)) / 6.0 /
                        m->force_per_volt_n;
    int k;
    for (k = 0; k < 6; k++) {
        double ref, u;
        switch (s->motion) {
        case 1: v[k] = 0.0; continue;
        case 2: v[k] = 10.0; continue;
        case 3: ref = 0.3; break;   /* beyond the top stop at 0.26 m */
        default:
            /* 8 mm sines at 0.7 Hz, phases 60 deg apart, with slow parts where carriages stick */
            ref = 0.008 * sin(2.0 * HG_PI * 0.7 * i * 1e-3 + k * HG_PI / 3.0);
            break;
        }
        if (s->velocity_mode)
            u = 300.0 * (ref - d->z_m[k]) * 0.05;   /* velocity command */
        else
            u = hold + 300.0 * (ref - d->z_m[k]);
        v[k] = u > 10.0 ? 10.0 : (u < -10.0 ? -10.0 : u);
    }
}

static void state_of(const hg_data *d, double x[NSTATE])
{
    memcpy(x, d->z_m, 6 * sizeof(double));
    memcpy(x + 6, d->zd_mps, 6 * sizeof(double));
    memcpy(x + 12, d->pose, 6 * sizeof(double));
    memcpy(x + 18, d->posed, 6 * sizeof(double));
    memcpy(x + 24, d->current_a, 6 * sizeof(double));
    memcpy(x + 30, d->zr_m, 6 * sizeof(double));
    memcpy(x + 36, d->zrd_mps, 6 * sizeof(double));
}

/* Run scenario s (flexible trains or rigid): its checkpoints into c (at
 * most STEPS / EVERY + 2); count. */
static int run(const scenario *s, int flexible, checkpoint *c)
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    const char *f, *w;
    int i, j, n = 0, rc = 0, sub = flexible ? flexible_substeps(s->integrator) : 1;
    hg_params_default(&p);
    if (flexible)
        p.backlash_m = s->backlash_m;
    else
        p.k_axial_n_per_m = 0.0;       /* the rigid drive train, as d20d9e5 had it */
    if (s->frictionless) {
        p.f_coulomb_n = 0.0;
        p.f_static_n = 0.0;
    }
    if (s->velocity_mode)
        p.amp_mode = 1.0;
    if (hg_model_init(&m, &p, (hg_model_kind)s->kind, &f, &w) || hg_model_set_integrator(&m, s->integrator) ||
        hg_data_reset(&m, &d)) {
        c[0].step = -1;
        c[0].rc = HG_ERR_BAD_PARAM;
        return 1;
    }
    for (i = 0; i < STEPS; i++) {
        double v[6];
        if (i == 200 && s->broken)
            d.broken_bars = s->broken;
        volts_of(s, &m, &d, i, v);
        for (j = 0; j < sub && rc == 0; j++)
            rc = hg_step(&m, &d, v, 1e-3 / sub);
        if (rc || (i + 1) % EVERY == 0) {
            c[n].step = i + 1;
            c[n].rc = rc;
            c[n].stuck = d.stuck;
            state_of(&d, c[n].x);
            n++;
        }
        if (rc)
            break;
    }
    return n;
}

static int write_file(const golden_set *g, const char *path)
{
    static checkpoint c[STEPS / EVERY + 2];
    FILE *fp = fopen(path, "w");
    int s, i, j, n;
    if (!fp)
        return 1;
    fprintf(fp, "# golden states of tests/unit/test_golden.c: scenario step rc stuck state[%d] (%%a)\n", g->nstate);
    for (s = 0; s < g->n; s++) {
        n = run(&g->sc[s], g->flexible, c);
        for (i = 0; i < n; i++) {
            fprintf(fp, "%d %d %d %u", s, c[i].step, c[i].rc, c[i].stuck);
            for (j = 0; j < g->nstate; j++)
                fprintf(fp, " %a", c[i].x[j]);
            fprintf(fp, "\n");
        }
    }
    return fclose(fp) != 0;
}

/* Largest |a - b| over x[from..to). */
static double maxdiff(const double *a, const double *b, int from, int to)
{
    double w = 0.0;
    int j;
    for (j = from; j < to; j++)
        w = fmax(w, fabs(a[j] - b[j]));
    return w;
}

/* Compare today's step with golden set g: one check per scenario. */
static void check_set(const golden_set *g)
{
    static checkpoint got[STEPS / EVERY + 2];
    static checkpoint want[NSCEN_MAX][STEPS / EVERY + 2];
    int nwant[NSCEN_MAX] = {0};
    char line[8192];
    FILE *fp = fopen(g->path, "r");
    int s;
    CHECK(fp != 0, "%s opens (run from the repository root)", g->path);
    if (!fp)
        return;
    while (fgets(line, sizeof line, fp)) {
        checkpoint c;
        char *q = line, *e;
        int j, sc;
        if (line[0] == '#')
            continue;
        sc = (int)strtol(q, &e, 10);
        if (e == q || sc < 0 || sc >= g->n || nwant[sc] >= STEPS / EVERY + 2)
            break;
        q = e;
        c.step = (int)strtol(q, &q, 10);
        c.rc = (int)strtol(q, &q, 10);
        c.stuck = (unsigned)strtoul(q, &q, 10);
        memset(c.x, 0, sizeof c.x);
        for (j = 0; j < g->nstate; j++)
            c.x[j] = strtod(q, &q);
        want[sc][nwant[sc]++] = c;
    }
    fclose(fp);
    for (s = 0; s < g->n; s++) {
        int n = run(&g->sc[s], g->flexible, got), i, same = 1, exact = 0;
        double dpos = 0.0, dvel = 0.0, dcur = 0.0;
        same = n == nwant[s];
        for (i = 0; same && i < n; i++) {
            const checkpoint *a = &got[i], *b = &want[s][i];
            same = a->step == b->step && a->rc == b->rc && a->stuck == b->stuck;
            dpos = fmax(dpos, fmax(maxdiff(a->x, b->x, 0, 6), maxdiff(a->x, b->x, 12, 18)));
            dvel = fmax(dvel, fmax(maxdiff(a->x, b->x, 6, 12), maxdiff(a->x, b->x, 18, 24)));
            dcur = fmax(dcur, maxdiff(a->x, b->x, 24, 30));
            if (g->flexible) {
                dpos = fmax(dpos, maxdiff(a->x, b->x, 30, 36));
                dvel = fmax(dvel, maxdiff(a->x, b->x, 36, 42));
            }
            exact += memcmp(a->x, b->x, (size_t)g->nstate * sizeof(double)) == 0;
        }
        CHECK(same && dpos <= 1e-12 && dvel <= 1e-9 && dcur <= 1e-9,
              "%s: %d checkpoints as %s (same failing step, code, stuck carriages), %d bit-identical; "
              "max diff %.3g m, %.3g m/s, %.3g A", g->sc[s].name, n, g->commit, exact, dpos, dvel, dcur);
    }
}

int main(int argc, char **argv)
{
    int g;
    if (argc == 4 && strcmp(argv[1], "--write") == 0 && (argv[2][0] == '0' || argv[2][0] == '1') &&
        argv[2][1] == 0)
        return write_file(&sets[argv[2][0] - '0'], argv[3]);
    for (g = 0; g < NSETS; g++)
        check_set(&sets[g]);
    return hg_test_exit();
}
