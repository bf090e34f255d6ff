/* hg_mujoco_model.c - write, load and read the MuJoCo model of the
 * Hexaglide (see hg_mujoco_model.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "hg_mujoco_model.h"

#define HGMJ_FILE "hexaglide.xml"

static const char *const hgmj_bar_name[6] = {"11", "12", "21", "22", "31", "32"};

/* Engine settings for a stiff, closed-loop machine at the 1 ms servo period:
 * - RK4: the project's own integrators are explicit and higher order; RK4
 *   keeps MuJoCo's integration error well below the constraint softness
 *   (Euler is offered for the speed comparison).
 * - Newton solver, tolerance 1e-12, up to 100 iterations: the loops are 18
 *   equality rows on a badly scaled mass matrix (52 kg of rotor inertia per
 *   carriage against a 0.03 kg m^2 head). With only equality rows (and the
 *   stops inactive) the solver's problem is quadratic and Newton ends in
 *   one iteration (measured: 1.00 on average), so the tight tolerance costs
 *   nothing and guards the steps where a hard stop engages.
 * - connect solref = (2 dt, 1): the shortest time constant MuJoCo accepts
 *   (it clamps anything below 2 timesteps), critically damped, so drift is
 *   pulled back within a few steps.
 * - connect solimp = (0.9999, 0.9999, ...): MuJoCo constraints are soft
 *   (impedance d: the constraint gets the fraction d of the force that
 *   would hold it exactly); 0.9999 is the largest MuJoCo accepts. Measured
 *   while the machine sinks from HOME (tests/engine): MuJoCo's defaults
 *   (0.02 s, 0.9) leave the loops 0.2 mm open, these settings 2 nm; in the
 *   bench's servo motion at most 2.3 um in the start-up transient and 0.2 um
 *   after it (it scales with solref[0]: 14 um at 5 ms, 0.16 mm at 20 ms).
 * - Tiny bar spin inertia: spin about the bar axis is a free, decoupled
 *   degree of freedom (both bar ends are point joints); MuJoCo needs it
 *   positive, the project neglects it.
 * - Hard stops: MuJoCo joint limits at [stop_min, stop_max] with MuJoCo's
 *   default soft-limit law, not the project's k_stop/c_stop spring-damper;
 *   the cross-checks stay well inside the stroke.
 * - No contacts: nothing in the machine collides, so collision detection
 *   is switched off (it would only cost time). */
void hgmj_options_default(hgmj_options *o)
{
    o->timestep_s = 1e-3;
    o->integrator = "RK4";
    o->iterations = 100;
    o->tolerance = 1e-12;
    o->eq_timeconst_s = 2.0 * o->timestep_s;
    o->eq_impedance = 0.9999;
    o->bar_spin_kgm2 = 1e-5;
    o->hard_stops = 1;
}

typedef struct {
    char *buf;
    size_t n, len;
    int overflow;
} hgmj_text;

/* Append printf-style text, remembering overflow. */
static void hgmj_put(hgmj_text *t, const char *fmt, ...)
{
    va_list ap;
    int k;
    if (t->overflow)
        return;
    va_start(ap, fmt);
    k = vsnprintf(t->buf + t->len, t->n - t->len, fmt, ap);
    va_end(ap);
    if (k < 0 || (size_t)k >= t->n - t->len) {
        t->overflow = 1;
        return;
    }
    t->len += (size_t)k;
}

double hgmj_force_per_volt(const hg_params *p)
{
    return p->ka_a_per_v * p->kt_nm_per_a * 2.0 * M_PI / p->lead_m;
}

void hgmj_peer_params(hg_params *p)
{
    hg_params_default(p);
    p->k_axial_n_per_m = 0.0;  /* rigid trains: the twin's rotor is its carriage's armature */
    p->f_coulomb_n = 0.0;
    p->f_static_n = 0.0;
    p->amp_mode = 0.0;
    p->l_winding_h = 1e-9;
    p->v_bus_v = 1e6;
}

void hgmj_peer_params_friction(hg_params *p)
{
    hg_params d;
    hgmj_peer_params(p);
    hg_params_default(&d);
    p->f_coulomb_n = d.f_coulomb_n;
    p->f_static_n = d.f_coulomb_n;
}

int hgmj_is_peer(const hg_params *p, const hgmj_options *o)
{
    return p->f_coulomb_n >= 0.0 && p->f_static_n == p->f_coulomb_n && p->amp_mode == 0.0 &&
           p->l_winding_h / p->r_winding_ohm < 1e-6 * o->timestep_s &&
           p->v_bus_v >= 1000.0 * p->r_winding_ohm * p->i_max_a && p->k_axial_n_per_m == 0.0;
}

int hgmj_write_mjcf(const hg_params *p, const hgmj_options *o, char *buf, size_t n)
{
    const hg_geometry *g = &p->geo;
    const double alpha[3] = {0.0, 2.0 * M_PI / 3.0, -2.0 * M_PI / 3.0};
    const double sgn[2] = {1.0, -1.0};
    /* bar inertia about its COM from the inertia about the carriage joint */
    const double i_bar_com = p->i_bar_kgm2 - p->m_bar_kg * 0.25 * g->l_m * g->l_m;
    /* bar tilt in its post's x-z plane: from B (lb, s e, h) down to A (lp, s e, 0) */
    const double tilt = atan2(g->lb_m - g->lp_m, hg_home_height(g));
    /* rotor inertia reflected to the carriage: inertia without weight */
    const double rotor_kg = p->j_rotor_kgm2 * pow(2.0 * M_PI / p->lead_m, 2);
    /* the drive saturates at the DAC range and at the amplifier's current limit */
    const double f_max = p->i_max_a * p->kt_nm_per_a * 2.0 * M_PI / p->lead_m;
    const double tiny = 1e-6; /* carriage rotational inertia: the slide cannot rotate */
    hgmj_text t = {buf, n, 0, 0};
    int i, j;

    if (!(hg_home_height(g) > 0.0) || !(i_bar_com > 0.0) ||
        !(p->m_head_kg > 0.0) || !(p->m_bar_kg > 0.0) || !(p->m_carriage_kg > 0.0) ||
        !(o->bar_spin_kgm2 > 0.0) || !(p->lead_m > 0.0))
        return -2;
    if (!hgmj_is_peer(p, o))
        return -3; /* breakaway friction and a real winding have no MuJoCo twin here */
    if (n > 0)
        buf[0] = 0;

    hgmj_put(&t, "<mujoco model=\"hexaglide\">\n"
                 "  <!-- generated by bench/hg_mujoco_model.c from hg_params: do not edit -->\n"
                 "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n");
    hgmj_put(&t, "  <option timestep=\"%.17g\" gravity=\"0 0 %.17g\" integrator=\"%s\"\n"
                 "          solver=\"Newton\" iterations=\"%d\" tolerance=\"%.17g\">\n"
                 "    <flag contact=\"disable\"/>\n"
                 "  </option>\n",
             o->timestep_s, -p->g_mps2, o->integrator, o->iterations, o->tolerance);
    hgmj_put(&t, "  <worldbody>\n");
    for (i = 0; i < 3; i++) {
        hgmj_put(&t, "    <body name=\"post%d\" euler=\"0 0 %.17g\">\n", i + 1, alpha[i]);
        for (j = 0; j < 2; j++) {
            const char *nm = hgmj_bar_name[2 * i + j];
            hgmj_put(&t, "      <body name=\"carriage%s\" pos=\"%.17g %.17g %.17g\">\n",
                     nm, g->lb_m, sgn[j] * g->e_m, hg_home_height(g));
            hgmj_put(&t, "        <joint name=\"z%s\" type=\"slide\" axis=\"0 0 1\" armature=\"%.17g\""
                         " damping=\"%.17g\"", nm, rotor_kg, p->c_visc_ns_per_m);
            if (o->hard_stops)
                hgmj_put(&t, " limited=\"true\" range=\"%.17g %.17g\"", p->stop_min_m, p->stop_max_m);
            if (p->f_coulomb_n > 0.0)   /* dry friction, as stiff as the loops */
                hgmj_put(&t, " frictionloss=\"%.17g\" solreffriction=\"%.17g 1\""
                             " solimpfriction=\"%.17g %.17g 0.001 0.5 2\"", p->f_coulomb_n,
                         o->eq_timeconst_s, o->eq_impedance, o->eq_impedance);
            hgmj_put(&t, "/>\n");
            hgmj_put(&t, "        <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%g %g %g\"/>\n",
                     p->m_carriage_kg, tiny, tiny, tiny);
            hgmj_put(&t, "        <body name=\"bar%s\" euler=\"0 %.17g 0\">\n", nm, tilt);
            hgmj_put(&t, "          <joint name=\"ball%s\" type=\"ball\"/>\n", nm);
            hgmj_put(&t, "          <inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
                     -0.5 * g->l_m, p->m_bar_kg, i_bar_com, i_bar_com, o->bar_spin_kgm2);
            hgmj_put(&t, "          <site name=\"end%s\" pos=\"0 0 %.17g\"/>\n", nm, -g->l_m);
            hgmj_put(&t, "        </body>\n      </body>\n");
        }
        hgmj_put(&t, "    </body>\n");
    }
    hgmj_put(&t, "    <body name=\"head\" pos=\"0 0 0\">\n"
                 "      <freejoint name=\"head\"/>\n"
                 "      <inertial pos=\"0 0 %.17g\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
             -p->head_com_m, p->m_head_kg, p->i_head_xx_kgm2, p->i_head_yy_kgm2, p->i_head_zz_kgm2);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 2; j++) {
            /* A_k in head coordinates: Rz(alpha_i) (lp, s_j e, 0) */
            double x = g->lp_m, y = sgn[j] * g->e_m, c = cos(alpha[i]), s = sin(alpha[i]);
            hgmj_put(&t, "      <site name=\"A%s\" pos=\"%.17g %.17g 0\"/>\n",
                     hgmj_bar_name[2 * i + j], c * x - s * y, s * x + c * y);
        }
    hgmj_put(&t, "    </body>\n  </worldbody>\n  <equality>\n");
    /* the anchor is in the bar's frame; MuJoCo finds the head-side point
     * from the initial (HOME) configuration, which is assembled */
    for (i = 0; i < 6; i++)
        hgmj_put(&t, "    <connect name=\"loop%s\" body1=\"bar%s\" body2=\"head\" anchor=\"0 0 %.17g\""
                     " solref=\"%.17g 1\" solimp=\"%.17g %.17g 0.001 0.5 2\"/>\n",
                 hgmj_bar_name[i], hgmj_bar_name[i], -g->l_m, o->eq_timeconst_s,
                 o->eq_impedance, o->eq_impedance);
    hgmj_put(&t, "  </equality>\n  <actuator>\n");
    for (i = 0; i < 6; i++)
        hgmj_put(&t, "    <motor name=\"drive%s\" joint=\"z%s\" gear=\"%.17g\" ctrllimited=\"true\""
                     " ctrlrange=\"-10 10\" forcelimited=\"true\" forcerange=\"%.17g %.17g\"/>\n",
                 hgmj_bar_name[i], hgmj_bar_name[i], hgmj_force_per_volt(p), -f_max, f_max);
    hgmj_put(&t, "  </actuator>\n</mujoco>\n");
    return t.overflow ? -1 : (int)t.len;
}

mjModel *hgmj_load(const hg_params *p, const hgmj_options *o, char *err, int err_sz)
{
    size_t cap = 1 << 16;
    char *xml = malloc(cap);
    mjVFS *vfs = malloc(sizeof *vfs);
    mjModel *m = 0;
    int len, f;

    if (!xml || !vfs) {
        snprintf(err, err_sz, "out of memory");
        goto out;
    }
    len = hgmj_write_mjcf(p, o, xml, cap);
    if (len < 0) {
        snprintf(err, err_sz, "%s", len == -1 ? "MJCF text longer than the 64 kB buffer"
                 : len == -2 ? "parameters not assembled at HOME (h != sqrt(l^2-(lb-lp)^2)) "
                               "or a mass property not positive: fix the parameter set"
                 : "the MuJoCo peer models neither breakaway (f_static above f_coulomb) nor the "
                   "winding: start from hgmj_peer_params or hgmj_peer_params_friction");
        goto out;
    }
    mj_defaultVFS(vfs);
    if (mj_makeEmptyFileVFS(vfs, HGMJ_FILE, len) != 0) {
        snprintf(err, err_sz, "cannot make the in-memory MJCF file");
        goto out;
    }
    f = mj_findFileVFS(vfs, HGMJ_FILE);
    memcpy(vfs->filedata[f], xml, (size_t)len);
    m = mj_loadXML(HGMJ_FILE, vfs, err, err_sz);
    mj_deleteVFS(vfs);
out:
    free(vfs);
    free(xml);
    return m;
}

int hgmj_index_build(const mjModel *m, hgmj_index *ix)
{
    char name[32];
    int k, id;
    for (k = 0; k < 6; k++) {
        snprintf(name, sizeof name, "z%s", hgmj_bar_name[k]);
        if ((id = mj_name2id(m, mjOBJ_JOINT, name)) < 0)
            return -1;
        ix->slide_qpos[k] = m->jnt_qposadr[id];
        ix->slide_dof[k] = m->jnt_dofadr[id];
        snprintf(name, sizeof name, "end%s", hgmj_bar_name[k]);
        if ((ix->bar_end_site[k] = mj_name2id(m, mjOBJ_SITE, name)) < 0)
            return -1;
        snprintf(name, sizeof name, "A%s", hgmj_bar_name[k]);
        if ((ix->head_joint_site[k] = mj_name2id(m, mjOBJ_SITE, name)) < 0)
            return -1;
    }
    if ((id = mj_name2id(m, mjOBJ_JOINT, "head")) < 0)
        return -1;
    ix->head_qpos = m->jnt_qposadr[id];
    ix->head_dof = m->jnt_dofadr[id];
    return 0;
}

double hgmj_connect_violation(const mjData *d, const hgmj_index *ix)
{
    double worst = 0.0;
    int k;
    for (k = 0; k < 6; k++) {
        const mjtNum *a = d->site_xpos + 3 * ix->bar_end_site[k];
        const mjtNum *b = d->site_xpos + 3 * ix->head_joint_site[k];
        double dist = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                           (a[2] - b[2]) * (a[2] - b[2]));
        if (dist > worst)
            worst = dist;
    }
    return worst;
}

void hgmj_joints(const mjData *d, const hgmj_index *ix, double z[6])
{
    int k;
    for (k = 0; k < 6; k++)
        z[k] = d->qpos[ix->slide_qpos[k]];
}

void hgmj_head_pose(const mjData *d, const hgmj_index *ix, double pose[6])
{
    const mjtNum *q = d->qpos + ix->head_qpos;
    mjtNum R[9];
    mju_quat2Mat(R, q + 3); /* row-major */
    pose[0] = q[0];
    pose[1] = q[1];
    pose[2] = q[2];
    pose[3] = atan2(R[7], R[8]);                   /* A about x */
    pose[4] = asin(fmax(-1.0, fmin(1.0, -R[6])));  /* B about y */
    pose[5] = atan2(R[3], R[0]);                   /* C about z */
}
