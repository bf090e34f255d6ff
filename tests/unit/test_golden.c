/* test_golden.c - the dynamics step gives today what commit d20d9e5 gave.
 *
 * tests/data/golden-d20d9e5.txt holds, for a set of scenarios, the state
 * hg_step reached at checkpoints, written as hexadecimal floats by this
 * very program built against commit d20d9e5 (the version before the step
 * was made cheaper, before the plant interface and the flexible drive
 * train). The independent fact is that earlier build's output: every
 * later change that claims to keep the answers (an optimization, the
 * rigid limit k_axial = 0 of the drive train, a refactoring) must give
 * the same numbers: every scenario runs with k_axial = 0. The scenarios cover every model kind and scheme,
 * stick and slip, the frictionless fused step, velocity-mode amplifiers,
 * a bus-limited dash, the drives off (a sink), a hard stop and a broken
 * bar; each step's failure code and the stuck carriages are compared too.
 *
 * Asserted per scenario: the same steps fail with the same codes, the
 * same carriages stick at every checkpoint, positions within 1e-12 m (and
 * rad), velocities within 1e-9 m/s (rad/s), currents within 1e-9 A; the
 * number of checkpoints that are bit-identical is reported.
 *   test_golden --write FILE   writes the file (done once, at d20d9e5) */
#include <stdlib.h>
#include <string.h>
#include "hg_test.h"
#include "hg_dynamics.h"
#include "hg_errors.h"
#include "hg_units.h"

#define STEPS 1200
#define EVERY 100
#define NSTATE 30            /* z, zd, pose, posed, current */

typedef struct {
    const char *name;
    int kind, integrator;
    int frictionless, velocity_mode;
    int motion;              /* 0 servo sines, 1 drives off (sink), 2 full volts up, 3 into the top stop */
    unsigned broken;         /* bars broken at step 200 */
} scenario;

static const scenario scenarios[] = {
    {"standard heun servo", HG_MODEL_STANDARD, HG_INTEGRATOR_HEUN, 0, 0, 0, 0},
    {"standard euler servo", HG_MODEL_STANDARD, HG_INTEGRATOR_IMPROVED_EULER, 0, 0, 0, 0},
    {"joints heun servo", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_HEUN, 0, 0, 0, 0},
    {"joints rk4 servo", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_RK4, 0, 0, 0, 0},
    {"cartesian heun servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0},
    {"cartesian euler servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 0, 0, 0, 0},
    {"cartesian rk4 servo", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_RK4, 0, 0, 0, 0},
    {"fused heun servo", HG_MODEL_FUSED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 0},
    {"fused euler frictionless", HG_MODEL_FUSED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 1, 0, 0, 0},
    {"cartesian euler frictionless", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_IMPROVED_EULER, 1, 0, 0, 0},
    {"cartesian heun velocity mode", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 1, 0, 0},
    {"cartesian heun sink", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 1, 0},
    {"joints heun sink", HG_MODEL_REDUCED_JOINTS, HG_INTEGRATOR_HEUN, 0, 0, 1, 0},
    {"cartesian heun full volts", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 2, 0},
    {"cartesian heun top stop", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 3, 0},
    {"cartesian heun bar 2 broken", HG_MODEL_REDUCED_CARTESIAN, HG_INTEGRATOR_HEUN, 0, 0, 0, 1u << 2},
    {"standard heun bar 0 broken", HG_MODEL_STANDARD, HG_INTEGRATOR_HEUN, 0, 0, 0, 1u << 0},
};
#define NSCEN ((int)(sizeof scenarios / sizeof scenarios[0]))

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
}

/* Run scenario s: its checkpoints into c (at most STEPS / EVERY + 2); count. */
static int run(const scenario *s, checkpoint *c)
{
    static hg_model m;
    static hg_data d;
    hg_params p;
    const char *f, *w;
    int i, n = 0, rc;
    hg_params_default(&p);
    p.k_axial_n_per_m = 0.0;           /* the rigid drive train, as d20d9e5 had it */
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
        rc = hg_step(&m, &d, v, 1e-3);
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

static int write_file(const char *path)
{
    static checkpoint c[STEPS / EVERY + 2];
    FILE *fp = fopen(path, "w");
    int s, i, j, n;
    if (!fp)
        return 1;
    fprintf(fp, "# golden states of tests/unit/test_golden.c: scenario step rc stuck state[%d] (%%a)\n", NSTATE);
    for (s = 0; s < NSCEN; s++) {
        n = run(&scenarios[s], c);
        for (i = 0; i < n; i++) {
            fprintf(fp, "%d %d %d %u", s, c[i].step, c[i].rc, c[i].stuck);
            for (j = 0; j < NSTATE; j++)
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

int main(int argc, char **argv)
{
    static checkpoint got[STEPS / EVERY + 2];
    static checkpoint want[NSCEN][STEPS / EVERY + 2];
    int nwant[NSCEN] = {0};
    char line[4096];
    FILE *fp;
    int s;
    if (argc == 3 && strcmp(argv[1], "--write") == 0)
        return write_file(argv[2]);
    fp = fopen("tests/data/golden-d20d9e5.txt", "r");
    CHECK(fp != 0, "tests/data/golden-d20d9e5.txt opens (run from the repository root)");
    if (!fp)
        return hg_test_exit();
    while (fgets(line, sizeof line, fp)) {
        checkpoint c;
        char *q = line, *e;
        int j, sc;
        if (line[0] == '#')
            continue;
        sc = (int)strtol(q, &e, 10);
        if (e == q || sc < 0 || sc >= NSCEN || nwant[sc] >= STEPS / EVERY + 2)
            break;
        q = e;
        c.step = (int)strtol(q, &q, 10);
        c.rc = (int)strtol(q, &q, 10);
        c.stuck = (unsigned)strtoul(q, &q, 10);
        for (j = 0; j < NSTATE; j++)
            c.x[j] = strtod(q, &q);
        want[sc][nwant[sc]++] = c;
    }
    fclose(fp);
    for (s = 0; s < NSCEN; s++) {
        int n = run(&scenarios[s], got), i, same = 1, exact = 0;
        double dpos = 0.0, dvel = 0.0, dcur = 0.0;
        same = n == nwant[s];
        for (i = 0; same && i < n; i++) {
            const checkpoint *a = &got[i], *b = &want[s][i];
            same = a->step == b->step && a->rc == b->rc && a->stuck == b->stuck;
            dpos = fmax(dpos, fmax(maxdiff(a->x, b->x, 0, 6), maxdiff(a->x, b->x, 12, 18)));
            dvel = fmax(dvel, fmax(maxdiff(a->x, b->x, 6, 12), maxdiff(a->x, b->x, 18, 24)));
            dcur = fmax(dcur, maxdiff(a->x, b->x, 24, 30));
            exact += memcmp(a->x, b->x, sizeof a->x) == 0;
        }
        CHECK(same && dpos <= 1e-12 && dvel <= 1e-9 && dcur <= 1e-9,
              "%s: %d checkpoints as d20d9e5 (same failing step, code, stuck carriages), %d bit-identical; "
              "max diff %.3g m, %.3g m/s, %.3g A", scenarios[s].name, n, exact, dpos, dvel, dcur);
    }
    return hg_test_exit();
}
