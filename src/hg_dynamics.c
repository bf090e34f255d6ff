/* hg_dynamics.c - the public dynamics API: model names, model
 * construction, reset at HOME and one checked integration step: the
 * model's scheme (hg_integrate.c) on the parametrization's accelerations
 * and stabilization (hg_step_*.c). */
#include "hg_math.h"
#include "hg_string.h"
#include "hg_dynamics.h"
#include "hg_system.h"
#include "hg_integrate.h"
#include "hg_step_joints.h"
#include "hg_step_standard.h"
#include "hg_step_cartesian.h"
#include "hg_step_broken.h"
#include "hg_forces.h"
#include "hg_stop.h"
#include "hg_drive.h"
#include "hg_friction.h"
#include "hg_linalg.h"
#include "hg_errors.h"
#include "hg_units.h"
#include "hg_gen_reduced.h"
#include "hg_gen_standard.h"

typedef char hg_consts_fit[(HG_GEN_REDUCED_NCONST <= HG_MAX_CONSTS &&
                            HG_GEN_STANDARD_NCONST <= HG_MAX_CONSTS) ? 1 : -1];

const char *const hg_model_names[HG_MODEL_COUNT] = {
    "standard", "reduced-joints", "reduced-cartesian", "fused-cartesian",
};

/* names[i] for 0 <= i < n, else 0. */
static const char *name_of(const char *const *names, int n, int i)
{
    return i >= 0 && i < n ? names[i] : 0;
}

/* Index of name in names[0..n), or -1 (also for a null name). */
static int index_of(const char *const *names, int n, const char *name)
{
    int i;
    for (i = 0; name && i < n; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

const char *hg_model_name(hg_model_kind kind)
{
    return name_of(hg_model_names, HG_MODEL_COUNT, (int)kind);
}

int hg_model_from_name(const char *name)
{
    return index_of(hg_model_names, HG_MODEL_COUNT, name);
}

int hg_model_set_integrator(hg_model *m, int which)
{
    if (which < 0 || which >= HG_INTEGRATOR_COUNT)
        return HG_ERR_BAD_PARAM;
    m->integrator = (hg_integrator)which;
    return 0;
}

/* hg_data -> state vectors of m's parametrization. */
static void pack(const hg_model *m, const hg_data *d, double *q, double *qd)
{
    int off = 6;
    memcpy(q, d->z_m, sizeof d->z_m);  /* memcpy: no aliasing, whole-vector moves */
    memcpy(qd, d->zd_mps, sizeof d->zd_mps);
    if (m->kind == HG_MODEL_STANDARD) {
        memcpy(q + 6, d->bar_rad, sizeof d->bar_rad);
        memcpy(qd + 6, d->bar_radps, sizeof d->bar_radps);
        off = 18;
    }
    memcpy(q + off, d->pose, sizeof d->pose);
    memcpy(qd + off, d->posed, sizeof d->posed);
}

/* hg_data -> q = [z, c], qd of the lumped-bar model (broken-bar step). */
static void lumped_pack(const hg_data *d, double *q, double *qd)
{
    memcpy(q, d->z_m, sizeof d->z_m);
    memcpy(q + 6, d->pose, sizeof d->pose);
    memcpy(qd, d->zd_mps, sizeof d->zd_mps);
    memcpy(qd + 6, d->posed, sizeof d->posed);
}

/* State vectors -> hg_data (positions, velocities, carriage accelerations). */
static void unpack(const hg_model *m, const double *q, const double *qd, const double *qdd,
                   hg_data *d)
{
    int off = 6;
    memcpy(d->z_m, q, sizeof d->z_m);
    memcpy(d->zd_mps, qd, sizeof d->zd_mps);
    if (qdd)
        memcpy(d->zdd_mps2, qdd, sizeof d->zdd_mps2);
    else
        memset(d->zdd_mps2, 0, sizeof d->zdd_mps2);
    if (m->kind == HG_MODEL_STANDARD) {
        memcpy(d->bar_rad, q + 6, sizeof d->bar_rad);
        memcpy(d->bar_radps, qd + 6, sizeof d->bar_radps);
        off = 18;
    }
    memcpy(d->pose, q + off, sizeof d->pose);
    memcpy(d->posed, qd + off, sizeof d->posed);
}

/* The state at HOME at rest in m's vectors: z = 0, dependent positions by
 * full Newton-Raphson, z' = 0 so d' = A z' = 0. 0 or a negative code. */
static int home_state(const hg_model *m, double *q, double *qd)
{
    int rc;
    memset(q, 0, HG_NQ_MAX * sizeof(double));
    memset(qd, 0, HG_NQ_MAX * sizeof(double));
    rc = hg_solve_positions(m, q);
    if (rc)
        return rc;
    if (!(hg_bar_length_error(&m->p.geo, q, q + hg_system_nq(m) - 6) <= HG_STAB_MAX_RESIDUAL_M))
        return HG_ERR_NO_CONVERGENCE;
    return 0;
}

int hg_data_reset(const hg_model *m, hg_data *d)
{
    double q[HG_NQ_MAX], qd[HG_NQ_MAX];
    int rc = home_state(m, q, qd);
    if (rc)
        return rc;
    memset(d, 0, HG_DATA_STATE_BYTES);
    unpack(m, q, qd, 0, d);
    d->amp_enabled = HG_BARS_ALL;      /* amplifiers on, no current yet */
    d->stuck = HG_BARS_ALL;            /* at rest: every carriage held by static friction */
    d->residual_m = hg_bar_length_error(&m->p.geo, d->z_m, d->pose);
    d->work.guard.valid = 0;
    d->work.guard.cones_valid = 0;
    memset(&d->work.drive, 0, sizeof d->work.drive);
    return 0;
}

void hg_friction_channel_of(const hg_params *p, hg_friction_channel *c)
{
    c->f_static_n = p->f_static_n;
    c->f_coulomb_n = p->f_coulomb_n;
    c->v_stribeck_mps = p->v_stribeck_mps;
}

double hg_friction_stribeck(const hg_params *p, double v)
{
    hg_friction_channel c;
    hg_friction_channel_of(p, &c);
    return hg_friction_shape(&c, v);
}

/* The drive fields of the Hexaglide's parameter set (every drive alike). */
static void drive_params_of(const hg_params *p, hg_drive_params *dp)
{
    dp->kt_nm_per_a = p->kt_nm_per_a;
    dp->lead_m = p->lead_m;
    dp->r_winding_ohm = p->r_winding_ohm;
    dp->l_winding_h = p->l_winding_h;
    dp->amp_mode = p->amp_mode;
    dp->ka_a_per_v = p->ka_a_per_v;
    dp->i_max_a = p->i_max_a;
    dp->v_bus_v = p->v_bus_v;
    dp->v_rated_mps = p->v_rated_mps;
    dp->kp_vel_as_per_m = p->kp_vel_as_per_m;
    dp->ki_vel_a_per_m = p->ki_vel_a_per_m;
}

int hg_model_init(hg_model *m, const hg_params *p, hg_model_kind kind,
                  const char **bad_field, const char **why)
{
    const double screw = 2.0 * HG_PI / p->lead_m;
    double q[HG_NQ_MAX], qd[HG_NQ_MAX], t;
    hg_drive_params dp;
    int rc, i;
    if ((int)kind < 0 || kind >= HG_MODEL_COUNT) {
        if (bad_field)
            *bad_field = "model";
        if (why)
            *why = "unknown parametrization";
        return HG_ERR_BAD_PARAM;
    }
    rc = hg_params_check(p, bad_field, why);
    if (rc)
        return rc;
    memset(m, 0, sizeof *m);
    m->p = *p;
    m->kind = kind;
    m->integrator = HG_INTEGRATOR_DEFAULT;
    drive_params_of(p, &dp);
    for (i = 0; i < 6; i++)
        hg_drive_init(&m->drive[i], &dp);
    m->force_per_volt_n = p->ka_a_per_v * m->drive[0].force_per_amp_n;
    for (i = 0; i < 6; i++)
        hg_friction_channel_of(p, &m->fric[i]);
    m->rotor_mass_kg = p->j_rotor_kgm2 * screw * screw;
    for (i = 0; i < 6; i++) {
        m->train[i].k_axial = p->k_axial_n_per_m;
        m->train[i].c_axial = p->c_axial_ns_per_m;
        m->train[i].backlash = p->backlash_m;
    }
    m->flexible = !hg_drivetrain_rigid(&m->train[0]);
    m->m_min_kg = m->flexible ? p->m_carriage_kg : p->m_carriage_kg + m->rotor_mass_kg;
    hg_guard_prepare(&p->geo, &m->guard);
    {
        hg_params pm = *p;            /* the machine whose carriages carry the rotors' inertia, or not */
        if (m->flexible)
            pm.j_rotor_kgm2 = 0.0;   /* the rotors are bodies of their own, behind the springs */
        if (kind == HG_MODEL_STANDARD)
            hg_gen_standard_init(&pm, m->k);
        else
            hg_gen_reduced_init(&pm, m->k);
        hg_gen_reduced_init(&pm, m->k_lumped);
    }
    if (!hg_all_finite(HG_MAX_CONSTS, m->k) || !hg_all_finite(HG_MAX_LUMPED_CONSTS, m->k_lumped)) {
        if (bad_field)
            *bad_field = "params";
        if (why)
            *why = "the model's constants are not finite";
        return HG_ERR_BAD_PARAM;
    }
    rc = home_state(m, q, qd);
    if (rc) {
        if (bad_field)
            *bad_field = "l";
        if (why)
            *why = "HOME (all carriages at 0) cannot be assembled with this geometry";
        return rc;
    }
    hg_model_energy(m, q, qd, &t, &m->potential_home_j);
    if (kind == HG_MODEL_STANDARD) {   /* [z, c] of the lumped-bar model */
        for (i = 0; i < 6; i++)
            q[6 + i] = q[18 + i];
    }
    hg_lumped_energy(m->k_lumped, q, qd, &t, &m->potential_lumped_home_j);
    return 0;
}

/* The broken-bar step on d's [z, c] with m's scheme: 0 with q1 (n of m's
 * kind, standard bar angles from the geometry, rates 0), qd1, qdd
 * filled, or a code. */
static int step_broken(const hg_model *m, hg_data *d, const double drive_n[6], const double fz[6],
                       double dt_s, double *q1, double *qd1, double *qdd, double *res)
{
    double q0[HG_NQ_REDUCED], qd0[HG_NQ_REDUCED], ql[HG_NQ_REDUCED], qdl[HG_NQ_REDUCED];
    double qddl[HG_NQ_REDUCED];
    int rc;
    lumped_pack(d, q0, qd0);
    rc = hg_integrate(m, m->integrator, &hg_broken_dae, d, q0, qd0, drive_n, fz, dt_s, ql, qdl,
                      qddl, res);
    if (rc)
        return rc;
    if (m->kind != HG_MODEL_STANDARD) {
        memcpy(q1, ql, sizeof ql);
        memcpy(qd1, qdl, sizeof qdl);
        memcpy(qdd, qddl, sizeof qddl);
        return 0;
    }
    memset(qd1, 0, HG_NQ_STANDARD * sizeof(double));
    memset(qdd, 0, HG_NQ_STANDARD * sizeof(double));
    memcpy(q1, ql, 6 * sizeof(double));
    memcpy(q1 + 6, d->bar_rad, sizeof d->bar_rad);
    memcpy(q1 + 18, ql + 6, 6 * sizeof(double));
    hg_bar_angles(&m->p, ql, ql + 6, q1 + 6);
    memcpy(qd1, qdl, 6 * sizeof(double));
    memcpy(qd1 + 18, qdl + 6, 6 * sizeof(double));
    memcpy(qdd, qddl, 6 * sizeof(double));
    memcpy(qdd + 18, qddl + 6, 6 * sizeof(double));
    return 0;
}

/* HG_ERR_THROUGH_STOP, with *r, when a carriage of z is deeper than
 * HG_THROUGH_STOP_M beyond a hard stop (a crash: the stop's spring does
 * not represent it), else 0. */
static int through_stop(const hg_params *p, const double z[6], hg_guard_report *r)
{
    int k;
    for (k = 0; k < 6; k++)
        if (z[k] < p->stop_min_m - HG_THROUGH_STOP_M || z[k] > p->stop_max_m + HG_THROUGH_STOP_M) {
            r->kind = HG_GUARD_THROUGH_STOP, r->bar = k, r->other = -1, r->value = z[k];
            r->limit = z[k] < p->stop_min_m ? p->stop_min_m : p->stop_max_m;
            return HG_ERR_THROUGH_STOP;
        }
    return 0;
}

double hg_step_dt_max_s(void)
{
    return HG_DT_MAX_S;
}

int hg_step(const hg_model *m, hg_data *d, const double volts[6], double dt_s)
{
    double q0[HG_NQ_MAX], qd0[HG_NQ_MAX], q1[HG_NQ_MAX], qd1[HG_NQ_MAX], qdd[HG_NQ_MAX];
    double fz[6], drive_n[6], res = 0.0;
    hg_drive_out drv;
    int n = hg_system_nq(m), rc, trig = 0, k, fric = hg_friction_any(m->fric, 6);
    if (!(isfinite(dt_s) && dt_s > 0.0 && dt_s <= HG_DT_MAX_S)) {
        d->last_error = HG_ERR_BAD_DT;
        return HG_ERR_BAD_DT;
    }
    pack(m, d, q0, qd0);
    /* the motors turn at the carriages' speed, or at the rotors' behind flexible trains */
    hg_drive_step(m->drive, 6, volts, d->current_a, m->flexible ? d->zrd_mps : d->zd_mps, d->vloop_int_m,
                  d->amp_enabled, dt_s, &d->work.drive, &drv);
    for (k = 0; k < 6; k++) {          /* drive, and the friction of the last step, held */
        double motor = drv.i_mean[k] * m->drive[k].force_per_amp_n;
        d->work.fric_est_n[k] = fric ? d->fric_n[k] : 0.0;
        if (!m->flexible) {
            drive_n[k] = motor + d->work.fric_est_n[k];
            continue;
        }
        /* flexible: the motor drives its rotor; the carriage feels the train (hg_integrate's stages) */
        d->work.motor_n[k] = motor;
        drive_n[k] = d->work.fric_est_n[k];
    }
    hg_carriage_forces(m, d->z_m, d->zd_mps, drive_n, fz);
    if (m->flexible)                   /* the trains' force at the step's start (the rotors' stage 0 too) */
        for (k = 0; k < 6; k++) {
            d->work.train_n[k] = hg_drivetrain_force(&m->train[k], d->zr_m[k] - d->z_m[k],
                                                     d->zrd_mps[k] - d->zd_mps[k]);
            fz[k] += d->work.train_n[k];
        }
    switch (d->broken_bars & HG_BARS_ALL ? HG_MODEL_COUNT : m->kind) {
    case HG_MODEL_COUNT:               /* a bar broken: any kind */
        rc = step_broken(m, d, drive_n, fz, dt_s, q1, qd1, qdd, &res);
        break;
    case HG_MODEL_STANDARD:
        rc = hg_integrate(m, m->integrator, &hg_standard_dae, d, q0, qd0, drive_n, fz, dt_s, q1, qd1,
                          qdd, &res);
        break;
    case HG_MODEL_REDUCED_JOINTS:
        rc = hg_integrate(m, m->integrator, &hg_joints_dae, d, q0, qd0, drive_n, fz, dt_s, q1, qd1,
                          qdd, &res);
        break;
    case HG_MODEL_FUSED_CARTESIAN:
        if (m->integrator == HG_INTEGRATOR_IMPROVED_EULER && !fric && !m->flexible) {
            double sc0[6];
            if (d->trig_valid && d->trig_key_rad[0] == d->pose[3] &&
                d->trig_key_rad[1] == d->pose[4] && d->trig_key_rad[2] == d->pose[5])
                memcpy(sc0, d->trig_sc, sizeof sc0);
            else
                hg_head_trig(d->pose, sc0);
            d->work.fric_stuck = 0;
            memset(d->work.fric_impulse, 0, sizeof d->work.fric_impulse);
            rc = hg_fused_step(m, d, q0, qd0, sc0, fz, dt_s, q1, qd1, qdd, &res);
            trig = 1;
            break;
        }
        /* other schemes, or friction: the generated accelerations, stage by stage */
        rc = hg_integrate(m, m->integrator, &hg_fused_dae, d, q0, qd0, drive_n, fz, dt_s, q1, qd1,
                          qdd, &res);
        trig = 1;
        break;
    case HG_MODEL_REDUCED_CARTESIAN:
        rc = hg_integrate(m, m->integrator, &hg_cartesian_dae, d, q0, qd0, drive_n, fz, dt_s, q1,
                          qd1, qdd, &res);
        trig = 1;
        break;
    default:
        rc = HG_ERR_BAD_PARAM;
    }
    if (rc == 0 && !(hg_all_finite(n, q1) && hg_all_finite(n, qd1) && hg_all_finite(n, qdd) &&
                     hg_all_finite(6, drv.i_end) &&
                     (!m->flexible || (hg_all_finite(6, d->work.rotor1_m) && hg_all_finite(6, d->work.rotor1_mps)))))
        rc = HG_ERR_STATE_NONFINITE;   /* the rotors and the currents too: no NaN into the state */
    if (rc == 0 && !(res <= HG_STAB_MAX_RESIDUAL_M))
        rc = HG_ERR_STABILIZATION;
    if (rc == 0) {                     /* the machine's mechanical limits, intact or broken */
        double sc[6];
        if (!trig)                     /* the Cartesian kinds' stabilization has them */
            hg_head_trig(q1 + n - 6, sc);
        rc = hg_guard_check_sc(&m->guard, q1, q1 + n - 6, trig ? d->work.sc1 : sc, d->broken_bars,
                               &d->work.guard, &d->guard);
    }
    if (rc == 0)
        rc = through_stop(&m->p, q1, &d->guard);
    if (rc) {
        d->last_error = rc;
        return rc;
    }
    if (m->flexible) {                 /* the velocity loops see the motors */
        hg_drive_integral(m->drive, 6, d->amp_enabled, &drv, d->zr_m, d->work.rotor1_m, dt_s, d->vloop_int_m);
        memcpy(d->zr_m, d->work.rotor1_m, sizeof d->zr_m);
        memcpy(d->zrd_mps, d->work.rotor1_mps, sizeof d->zrd_mps);
    } else {
        hg_drive_integral(m->drive, 6, d->amp_enabled, &drv, q0, q1, dt_s, d->vloop_int_m);
    }
    unpack(m, q1, qd1, qdd, d);
    d->trig_valid = trig;
    if (trig) {
        memcpy(d->trig_key_rad, d->pose + 3, sizeof d->trig_key_rad);
        memcpy(d->trig_sc, d->work.sc1, sizeof d->trig_sc);
    }
    memcpy(d->current_a, drv.i_end, sizeof d->current_a);
    for (k = 0; k < 6; k++) {          /* the step's mean force: smooth part at the start + friction */
        d->fric_n[k] = d->work.fric_impulse[k] / dt_s;
        d->force_n[k] = fz[k] - d->work.fric_est_n[k] + d->fric_n[k];
    }
    d->stuck = d->work.fric_stuck;
    d->residual_m = res;
    d->t_s += dt_s;
    d->last_error = 0;
    return 0;
}

/* The flexible trains' share: the rotors' kinetic energy and the springs'. */
static void train_energy(const hg_model *m, const hg_data *d, double *kinetic_j, double *potential_j)
{
    int k;
    if (!m->flexible)
        return;                        /* rigid: the rotors are in the machine's mass matrix */
    for (k = 0; k < 6; k++) {
        *kinetic_j += 0.5 * m->rotor_mass_kg * d->zrd_mps[k] * d->zrd_mps[k];
        *potential_j += hg_drivetrain_energy(&m->train[k], d->zr_m[k] - d->z_m[k]);
    }
}

void hg_energy(const hg_model *m, const hg_data *d, double *kinetic_j, double *potential_j)
{
    double q[HG_NQ_MAX], qd[HG_NQ_MAX], v;
    if (d->broken_bars & HG_BARS_ALL) {
        lumped_pack(d, q, qd);
        hg_lumped_energy(m->k_lumped, q, qd, kinetic_j, &v);
        *potential_j = v - m->potential_lumped_home_j;
    } else {
        pack(m, d, q, qd);
        hg_model_energy(m, q, qd, kinetic_j, &v);
        *potential_j = v - m->potential_home_j;
    }
    train_energy(m, d, kinetic_j, potential_j);
}
