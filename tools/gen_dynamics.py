#!/usr/bin/python3
"""gen_dynamics.py - derive the Hexaglide dynamics with SymPy and write C.

For each parametrization of the paper's section 7 (Ros et al. 2011) this
derives the constraint equations Phi(q), their Jacobians, the term
gamma = d/dt(Phi_q) q', the mass matrix M(q) and the generalized forces
(gravity minus the velocity terms) by the virtual-power route, then writes C
into src/generated/:

  hg_gen_reduced.[ch]   q = [z(6), c(6)]: bars lumped into exact point masses
                        (Reduced Joints, Reduced Cartesian) and the fused
                        Reduced Cartesian accelerations (the paper's future work)
  hg_gen_standard.[ch]  q = [z(6), a(12), c(6)]: bars as rigid bodies

Code generation: parameter-only subexpressions are hoisted into an init
function that fills k[] once from hg_params; the state-dependent rest is
common-subexpression eliminated (sympy.cse, the paper's atomization) and
printed as straight-line C without pow().

Usage: /usr/bin/python3 tools/gen_dynamics.py [--out DIR] [--check-only]
Needs SymPy 1.11.1 exactly (Debian 12 python3-sympy): the output must not
depend on the SymPy version, so other versions are refused.
"""
import os
import sys

REQUIRED_SYMPY = "1.11.1"
GENERATOR = "tools/gen_dynamics.py"

import sympy as sp  # noqa: E402
from sympy.printing.c import C99CodePrinter  # noqa: E402

# ---------------------------------------------------------------------------
# parameters: sympy symbol -> C expression reading hg_params *p
PARAM_FIELDS = [
    ("l", "p->geo.l_m"), ("lb", "p->geo.lb_m"), ("e", "p->geo.e_m"),
    ("lp", "p->geo.lp_m"), ("h", "hg_home_height(&p->geo)"), ("g", "p->g_mps2"),
    ("m_head", "p->m_head_kg"), ("head_com", "p->head_com_m"),
    ("i_head_xx", "p->i_head_xx_kgm2"), ("i_head_yy", "p->i_head_yy_kgm2"),
    ("i_head_zz", "p->i_head_zz_kgm2"), ("m_bar", "p->m_bar_kg"),
    ("i_bar", "p->i_bar_kgm2"), ("m_carriage", "p->m_carriage_kg"),
    ("lead", "p->lead_m"), ("j_rotor", "p->j_rotor_kgm2"),
]
P = {name: sp.Symbol("p_" + name, positive=True) for name, _ in PARAM_FIELDS}
PARAM_C = {P[name]: c for name, c in PARAM_FIELDS}
PARAMS = set(P.values())

POST_ANGLES = [0, 2 * sp.pi / 3, -2 * sp.pi / 3]
SIGNS = [1, -1]


def Rz(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def Ry(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a)], [0, 1, 0], [-sp.sin(a), 0, sp.cos(a)]])


def Rx(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def post_point(k, radial):
    """Rz(alpha_i) (radial, s_j e, 0) for bar k = 2(i-1)+(j-1)."""
    i, j = divmod(k, 2)
    return sp.simplify(Rz(POST_ANGLES[i]) * sp.Matrix([radial, SIGNS[j] * P["e"], 0]))


def derived_masses():
    """Exact lumping of a bar: 2 m_end + m_mid = m_bar, m_end l^2 + m_mid l^2/4 = i_bar."""
    me, mm = sp.symbols("me mm")
    sol = sp.solve([2 * me + mm - P["m_bar"],
                    me * P["l"] ** 2 + mm * P["l"] ** 2 / 4 - P["i_bar"]], [me, mm], dict=True)[0]
    return sp.simplify(sol[me]), sp.simplify(sol[mm])


# ---------------------------------------------------------------------------
# mechanics helpers (Kane / Jourdain route)
class System:
    """Accumulates M(q) and Q(q, q') = forces - velocity terms."""

    def __init__(self, q, qd):
        self.q, self.qd = q, qd
        n = len(q)
        self.M = sp.zeros(n, n)
        self.Q = sp.zeros(n, 1)
        self.V = sp.Integer(0)

    def jac(self, pos):
        return pos.jacobian(self.q)

    def bias(self, J):
        """J' q' = d(J q')/dq q'."""
        return (J * self.qd).jacobian(self.q) * self.qd

    def pair(self, coef, pos_a, pos_b):
        """Kinetic term coef * pos_a' . pos_b' (both orders when a != b)."""
        Ja, Jb = self.jac(pos_a), self.jac(pos_b)
        self.M += coef * Ja.T * Jb
        self.Q -= coef * Ja.T * self.bias(Jb)
        if pos_a != pos_b:
            self.M += coef * Jb.T * Ja
            self.Q -= coef * Jb.T * self.bias(Ja)

    def point(self, coef, pos):
        self.pair(coef, pos, pos)

    def rigid_body(self, mass, pos_com, R, angles, angle_rates, inertia):
        """Head: translation of the COM plus rotation with body angular velocity."""
        self.point(mass, pos_com)
        self.rotation(R, angles, angle_rates, inertia)

    def rotation(self, R, angles, angle_rates, inertia):
        """Rotational kinetic energy 1/2 wb^T inertia wb, wb the body angular velocity."""
        Rd = sp.zeros(3, 3)
        for a, ad in zip(angles, angle_rates):
            Rd += R.diff(a) * ad
        W = sp.simplify(R.T * Rd)
        wb = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
        Jw = wb.jacobian(self.qd)
        wbias = self.bias(Jw)
        self.M += Jw.T * inertia * Jw
        self.Q -= Jw.T * (inertia * wbias + wb.cross(inertia * wb))

    def weight(self, mass, pos):
        self.V += mass * P["g"] * pos[2]

    def finish(self):
        self.Q -= sp.Matrix([self.V]).jacobian(self.q).T


def constraint_terms(phi, q, qd):
    Jq = phi.jacobian(q)
    gamma = (Jq * qd).jacobian(q) * qd
    return Jq, gamma


def head_rotation(c):
    return Rz(c[5]) * Ry(c[4]) * Rx(c[3])


def composite_head(pts, m_pt):
    """The head plus a point mass m_pt at each joint as one rigid body:
    mass, COM (head frame) and inertia about the COM, all parameter-only."""
    s_head = sp.Matrix([0, 0, -P["head_com"]])
    mH = P["m_head"] + 6 * m_pt
    sG = sp.simplify((P["m_head"] * s_head + m_pt * sum(pts, sp.zeros(3, 1))) / mH)

    def about(rr, m):
        d = rr - sG
        return m * ((d.T * d)[0] * sp.eye(3) - d * d.T)
    IG = sp.diag(P["i_head_xx"], P["i_head_yy"], P["i_head_zz"]) + about(s_head, P["m_head"])
    for rr in pts:
        IG += about(rr, m_pt)
    return mH, sG, IG.applyfunc(lambda x: sp.simplify(sp.expand(x)))


# ---------------------------------------------------------------------------
# the two coordinate sets
def reduced_model():
    z = sp.symbols("z0:6")
    c = sp.symbols("X Y Z A B C")
    zd = sp.symbols("zd0:6")
    cd = sp.symbols("Xd Yd Zd Ad Bd Cd")
    q, qd = sp.Matrix(z + c), sp.Matrix(zd + cd)
    me, mm = derived_masses()
    m_rot = P["j_rotor"] * (2 * sp.pi / P["lead"]) ** 2
    R = head_rotation(c)
    Pp = sp.Matrix(c[:3])
    # head plus the lumped bar ends at its joints: one rigid body, its
    # mass, COM and inertia about the COM are parameter-only (init)
    m_pt = me + mm / 4
    pts = [post_point(k, P["lp"]) for k in range(6)]
    s_head = sp.Matrix([0, 0, -P["head_com"]])
    mH, sG, IG = composite_head(pts, m_pt)
    sysm = System(q, qd)
    sysm.rigid_body(mH, Pp + R * sG, R, c[3:], cd[3:], IG)
    phi = []
    for k in range(6):
        B = post_point(k, P["lb"]) + sp.Matrix([0, 0, P["h"] + z[k]])
        A = Pp + R * pts[k]
        # carriage, rotor and the lumped bar mass that moves with it
        sysm.point(P["m_carriage"] + m_rot + me + mm / 4, B)
        sysm.pair(mm / 4, A, B)            # cross term of the mid mass
        sysm.weight(P["m_carriage"] + me, B)
        sysm.weight(mm, (A + B) / 2)
        sysm.weight(me, A)
        d = B - A
        phi.append((d.T * d)[0] - P["l"] ** 2)
    sysm.weight(P["m_head"], Pp + R * s_head)
    sysm.finish()
    phi = sp.Matrix(phi)
    Jq, gamma = constraint_terms(phi, q, qd)
    return dict(q=q, qd=qd, M=sysm.M, Q=sysm.Q, V=sysm.V, phi=phi, Jq=Jq, gamma=gamma)


class Atoms:
    """Intermediate quantities of the generated code (the paper's
    atomization, in levels): each level only uses the state and earlier
    levels, so it can be CSE'd and printed before the next."""

    def __init__(self):
        self.levels = []

    def level(self):
        self.levels.append([])

    def vec(self, name, exprs):
        out = []
        for i, x in enumerate(exprs):
            x = sp.sympify(x)
            if x.is_Number or x.free_symbols <= PARAMS:
                out.append(x)      # zeros and constants stay literal
            else:
                s = sp.Symbol("%s%d" % (name, i))
                self.levels[-1].append((s, x))
                out.append(s)
        return sp.Matrix(out)


def reduced_kinematics(q, qd, atoms, with_velocity=True):
    """Level-1 atoms of the head: offsets r_k = R a_k of its joints and,
    with velocities, the world angular-velocity Jacobian E (w = E c_ang'),
    w and the velocity-product angular acceleration E' c_ang'. All derived
    by SymPy from R(A, B, C)."""
    c = q[6:, 0]
    R = head_rotation(c)
    pts = [post_point(k, P["lp"]) for k in range(6)]
    atoms.level()
    r = [atoms.vec("r%d_" % k, R * pts[k]) for k in range(6)]
    kin = dict(R=R, r=r, pts=pts)
    if with_velocity:
        cd = qd[6:, 0]
        Rd = sp.zeros(3, 3)
        for a, ad in zip(c[3:], cd[3:]):
            Rd += R.diff(a) * ad
        W = sp.simplify(Rd * R.T)
        w_flat = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
        E_flat = w_flat.jacobian(cd[3:])
        ab_flat = (E_flat * sp.Matrix(cd[3:])).jacobian(c[3:]) * sp.Matrix(cd[3:])
        E = [atoms.vec("e%d_" % j, E_flat[:, j]) for j in range(3)]
        kin.update(E=E, w=atoms.vec("w", w_flat), alpha=atoms.vec("al", ab_flat))
    return kin


def reduced_atomized(q, qd):
    """The reduced model in atomized form: the same M, Q, Phi, Phi_q, gamma
    and V as reduced_model() (the flat reference), written with rigid-body
    kinematics of the head so that the generated code stays short."""
    z, zd = q[:6, 0], qd[:6, 0]
    Pp, Pd = sp.Matrix(q[6:9, 0]), sp.Matrix(qd[6:9, 0])
    me, mm = derived_masses()
    m_rot = P["j_rotor"] * (2 * sp.pi / P["lead"]) ** 2
    m_pt = me + mm / 4
    mq = mm / 4
    atoms = Atoms()
    kin = reduced_kinematics(q, qd, atoms)
    R, r, pts, E, w, alpha = kin["R"], kin["r"], kin["pts"], kin["E"], kin["w"], kin["alpha"]
    # composite head: inertial body (lumped m_end + m_mid/4 at each joint)
    # and weight body (m_end + m_mid/2 at each joint), parameter-only
    s_head = sp.Matrix([0, 0, -P["head_com"]])
    mH, sG, IG = composite_head(pts, m_pt)
    WH = P["g"] * (P["m_head"] + 6 * (me + mm / 2))
    sW = sp.simplify(P["g"] * (P["m_head"] * s_head + (me + mm / 2) * sum(pts, sp.zeros(3, 1))) / WH)
    s = atoms.vec("sg", R * sG)
    sw = atoms.vec("sw", R * sW)
    # rotation in the head frame, where the composite inertia IG is
    # parameter-only: body angular velocity wb = Eb c_ang' (Eb = R^T E needs
    # only products of the angles' sin/cos) and its velocity-product rate
    # Eb' c_ang'; E^T Iw E = Eb^T IG Eb and E^T (Iw alpha + w x Iw w) =
    # Eb^T (IG alb + wb x IG wb) since w = R wb and alpha = R alb
    ca, cda = q[9:12, 0], qd[9:12, 0]
    Rd = sp.zeros(3, 3)
    for a, ad in zip(ca, cda):
        Rd += R.diff(a) * ad
    Wb = sp.simplify(R.T * Rd)
    wb_flat = sp.Matrix([Wb[2, 1], Wb[0, 2], Wb[1, 0]])
    Eb_flat = wb_flat.jacobian(cda)
    alb_flat = (Eb_flat * sp.Matrix(cda)).jacobian(ca) * sp.Matrix(cda)
    Eb = [atoms.vec("eb%d_" % j, Eb_flat[:, j]) for j in range(3)]
    wb = atoms.vec("wb", wb_flat)
    alb = atoms.vec("alb", alb_flat)
    # level 2: per joint and head vectors
    atoms.level()
    ez = sp.Matrix([0, 0, 1])
    d, dd, ab, n = [], [], [], []
    for k in range(6):
        B = post_point(k, P["lb"]) + sp.Matrix([0, 0, P["h"] + z[k]])
        d.append(atoms.vec("d%d_" % k, B - Pp - r[k]))
        v = atoms.vec("v%d_" % k, w.cross(r[k]))
        dd.append(atoms.vec("dd%d_" % k, zd[k] * ez - Pd - v))
        ab.append(atoms.vec("ab%d_" % k, alpha.cross(r[k]) + w.cross(v)))
        n.append(atoms.vec("n%d_" % k, r[k].cross(d[k])))
    vs = atoms.vec("vs", w.cross(s))
    agb = atoms.vec("ag", alpha.cross(s) + w.cross(vs))
    f = [atoms.vec("f%d_" % j, s.cross(E[j])) for j in range(3)]
    Iww = atoms.vec("iww", IG * wb)
    gyro = atoms.vec("gy", IG * alb + wb.cross(Iww))
    IE = [atoms.vec("ie%d_" % j, IG * Eb[j]) for j in range(3)]
    # outputs
    M = sp.zeros(12, 12)
    Q = sp.zeros(12, 1)
    phi = sp.zeros(6, 1)
    Jq = sp.zeros(6, 12)
    gamma = sp.zeros(6, 1)
    V = sp.Integer(0)
    for k in range(6):
        M[k, k] = P["m_carriage"] + m_rot + me + mq
        M[k, 8] = M[8, k] = mq
        for j in range(3):
            M[k, 9 + j] = M[9 + j, k] = -mq * (r[k][0] * E[j][1] - r[k][1] * E[j][0])
        Q[k] = -mq * ab[k][2] - P["g"] * (P["m_carriage"] + me + mm / 2)
        V += P["g"] * (P["m_carriage"] + me + mm / 2) * z[k]
        phi[k] = (d[k].T * d[k])[0] - P["l"] ** 2
        Jq[k, k] = 2 * d[k][2]
        for j in range(3):
            Jq[k, 6 + j] = -2 * d[k][j]
            Jq[k, 9 + j] = -2 * (n[k].T * E[j])[0]
        gamma[k] = 2 * (dd[k].T * dd[k])[0] - 2 * (d[k].T * ab[k])[0]
    for i in range(3):
        M[6 + i, 6 + i] = mH
        for j in range(3):
            M[6 + i, 9 + j] = M[9 + j, 6 + i] = -mH * f[j][i]
            M[9 + i, 9 + j] = mH * (f[i].T * f[j])[0] + (Eb[i].T * IE[j])[0]
        Q[6 + i] = -mH * agb[i]
        Q[9 + i] = mH * (f[i].T * agb)[0] - (Eb[i].T * gyro)[0] \
            - WH * (E[i][0] * sw[1] - E[i][1] * sw[0])
    Q[8] -= WH
    V += WH * (Pp[2] + sw[2])
    return dict(levels=atoms.levels, M=M, Q=Q, phi=phi, Jq=Jq, gamma=gamma, V=V)


def reduced_stabilize_atomized(q, qd):
    """phi, Phi_z and Phi_c c' = -2 d.(P' + w x r) of the reduced model."""
    z, Pp, Pd = q[:6, 0], sp.Matrix(q[6:9, 0]), sp.Matrix(qd[6:9, 0])
    atoms = Atoms()
    kin = reduced_kinematics(q, qd, atoms)
    r, w = kin["r"], kin["w"]
    atoms.level()
    phi, pz, vc = sp.zeros(6, 1), sp.zeros(6, 1), sp.zeros(6, 1)
    for k in range(6):
        B = post_point(k, P["lb"]) + sp.Matrix([0, 0, P["h"] + z[k]])
        d = atoms.vec("d%d_" % k, B - Pp - r[k])
        phi[k] = (d.T * d)[0] - P["l"] ** 2
        pz[k] = 2 * d[2]
        vc[k] = -2 * (d.T * (Pd + w.cross(r[k])))[0]
    return dict(levels=atoms.levels, phi=phi, Phi_z=pz, vc=vc)


def reduced_constraints_atomized(q):
    """phi and Phi_q of the reduced model with the head offsets as atoms."""
    z, Pp = q[:6, 0], sp.Matrix(q[6:9, 0])
    atoms = Atoms()
    kin = reduced_kinematics(q, None, atoms, with_velocity=False)
    r = kin["r"]
    c = q[6:, 0]
    R = kin["R"]
    Rd = [R.diff(a) for a in c[3:]]
    atoms.level()
    phi = sp.zeros(6, 1)
    Jq = sp.zeros(6, 12)
    for k in range(6):
        B = post_point(k, P["lb"]) + sp.Matrix([0, 0, P["h"] + z[k]])
        d = atoms.vec("d%d_" % k, B - Pp - r[k])
        phi[k] = (d.T * d)[0] - P["l"] ** 2
        Jq[k, k] = 2 * d[2]
        for j in range(3):
            Jq[k, 6 + j] = -2 * d[j]
            Jq[k, 9 + j] = -2 * (d.T * (Rd[j] * kin["pts"][k]))[0]
    return dict(levels=atoms.levels, phi=phi, Jq=Jq)


def standard_model():
    z = sp.symbols("z0:6")
    a = sp.symbols("a0:12")
    c = sp.symbols("X Y Z A B C")
    zd = sp.symbols("zd0:6")
    ad = sp.symbols("ad0:12")
    cd = sp.symbols("Xd Yd Zd Ad Bd Cd")
    q, qd = sp.Matrix(z + a + c), sp.Matrix(zd + ad + cd)
    m_rot = P["j_rotor"] * (2 * sp.pi / P["lead"]) ** 2
    R = head_rotation(c)
    Pp = sp.Matrix(c[:3])
    s_head = sp.Matrix([0, 0, -P["head_com"]])
    sysm = System(q, qd)
    sysm.rigid_body(P["m_head"], Pp + R * s_head, R, c[3:], cd[3:],
                    sp.diag(P["i_head_xx"], P["i_head_yy"], P["i_head_zz"]))
    sysm.weight(P["m_head"], Pp + R * s_head)
    phi = []
    for k in range(6):
        B = post_point(k, P["lb"]) + sp.Matrix([0, 0, P["h"] + z[k]])
        ph, th = a[2 * k], a[2 * k + 1]
        # u = Rx(ph) Ry(th) (0,0,-1): pole along x, never reached by a bar
        u = sp.Matrix([-sp.sin(th), sp.sin(ph) * sp.cos(th), -sp.cos(ph) * sp.cos(th)])
        A = Pp + R * post_point(k, P["lp"])
        # T_bar = 1/2 m |B'|^2 + m l/2 B'.u' + 1/2 i_bar |u'|^2
        sysm.point(P["m_carriage"] + m_rot + P["m_bar"], B)
        sysm.pair(P["m_bar"] * P["l"] / 2, B, u)
        sysm.point(P["i_bar"], u)
        sysm.weight(P["m_carriage"], B)
        sysm.weight(P["m_bar"], B + P["l"] / 2 * u)
        phi.extend(list(B + P["l"] * u - A))
    sysm.finish()
    phi = sp.Matrix(phi)
    Jq, gamma = constraint_terms(phi, q, qd)
    return dict(q=q, qd=qd, M=sysm.M, Q=sysm.Q, V=sysm.V, phi=phi, Jq=Jq, gamma=gamma)


# ---------------------------------------------------------------------------
# code generation
class Printer(C99CodePrinter):
    """C printer: constants as k[i], states as q[i]/qd[i], no pow()."""

    def __init__(self, names):
        super().__init__()
        self.names = names

    def _print_Symbol(self, s):
        return self.names.get(s, s.name)

    def _print_Pow(self, e):
        b, x = e.base, e.exp
        if x == sp.Rational(1, 2):
            return "sqrt(%s)" % self._print(b)
        if x.is_Integer and 1 < x <= 4:
            pb = self.parenthesize(b, 60)
            return "(%s)" % "*".join([pb] * int(x))
        if x.is_Integer and -4 <= x < 0:
            return "1.0/(%s)" % self._print(b ** (-x))
        raise ValueError("unsupported power %s" % e)

    def _print_Rational(self, e):
        return "%d.0/%d.0" % (e.p, e.q)

    def _print_Pi(self, e):
        return "HG_PI"                 # the project's pi (hg_units.h): strict C99 has no M_PI


class Hoister:
    """Replace parameter-only subexpressions by constants k[i]."""

    def __init__(self):
        self.consts = {}     # expr -> symbol
        self.order = []      # (symbol, expr)

    def const(self, e):
        if e not in self.consts:
            s = sp.Symbol("K%d" % len(self.order))
            self.consts[e] = s
            self.order.append((s, e))
        return self.consts[e]

    def is_const(self, e):
        return e.free_symbols <= PARAMS

    def __call__(self, e):
        if e.is_Number:
            return e
        if self.is_const(e):
            return self.const(e)
        if e.is_Atom:
            return e
        if e.is_Add or e.is_Mul:
            cargs = [x for x in e.args if self.is_const(x) and not x.is_Number]
            nums = [x for x in e.args if x.is_Number]
            rest = [self(x) for x in e.args if not self.is_const(x)]
            parts = nums + rest
            if cargs:
                parts.insert(0, self.const(e.func(*cargs)))
            return e.func(*parts)
        return e.func(*[self(x) for x in e.args])


def count_flops(exprs):
    return int(sum(sp.count_ops(x) for x in exprs))


def emit_block(assigns, printer, prefix, indent="    "):
    """assigns: list of (lhs C string, expr). CSE and print; returns (lines, flops)."""
    exprs = [x for _, x in assigns]
    reps, red = sp.cse(exprs, symbols=sp.numbered_symbols(prefix), optimizations="basic")
    lines = []
    flops = 0
    for s, x in reps:
        lines.append("%sconst double %s = %s;" % (indent, s.name, printer.doprint(x)))
        flops += count_flops([x])
    for (lhs, _), x in zip(assigns, red):
        lines.append("%s%s = %s;" % (indent, lhs, printer.doprint(x)))
        flops += count_flops([x])
    return lines, flops


def prune(levels, exprs):
    """Drop atoms that no output (and no kept atom) uses."""
    used = set()
    for x in exprs:
        used |= x.free_symbols
    kept = []
    for lev in reversed(levels):
        keep = []
        for sy, x in reversed(lev):     # atoms may use earlier atoms of their level
            if sy in used:
                keep.insert(0, (sy, x))
                used |= x.free_symbols
        kept.insert(0, keep)
    return kept


def emit_levels(levels, printer, indent="    "):
    """Hoisted atoms level by level: CSE, print; returns (lines, flops)."""
    lines, flops = [], 0
    for li, lev in enumerate(levels):
        if not lev:
            continue
        hx = [x for _, x in lev]
        reps, red = sp.cse(hx, symbols=sp.numbered_symbols("u%d_" % li), optimizations="basic")
        for sy, x in reps:
            lines.append("%sconst double %s = %s;" % (indent, sy.name, printer.doprint(x)))
            flops += count_flops([x])
        for (sy, _), x in zip(lev, red):
            lines.append("%sconst double %s = %s;" % (indent, sy.name, printer.doprint(x)))
            flops += count_flops([x])
    return lines, flops


TRIG_SYMS = sp.symbols("sA cA sB cB sC cC")


def trig_inputs(c):
    """sin/cos of the head angles as inputs sc[6] = sA cA sB cB sC cC: the
    caller computes them once per state (and can reuse them between the
    stabilization of one step and the terms of the next)."""
    sub, names = {}, {}
    for i, a in enumerate(c[3:]):
        sub[sp.sin(a)] = TRIG_SYMS[2 * i]
        sub[sp.cos(a)] = TRIG_SYMS[2 * i + 1]
    for i, t in enumerate(TRIG_SYMS):
        names[t] = "sc[%d]" % i
    return sub, names


def state_names(q, qd):
    names = {}
    for i, s in enumerate(q):
        names[s] = "q[%d]" % i
    for i, s in enumerate(qd):
        names[s] = "qd[%d]" % i
    return names


def matrix_assigns(name, Mx, rows=None, cols=None, skip_zero=True):
    rows = range(Mx.shape[0]) if rows is None else rows
    cols = range(Mx.shape[1]) if cols is None else cols
    out = []
    ncol = len(cols)
    for ii, i in enumerate(rows):
        for jj, j in enumerate(cols):
            out.append(("%s[%d]" % (name, ii * ncol + jj), Mx[i, j]))
    return out


class Unit:
    """One generated .c/.h pair sharing a constant table k[]."""

    def __init__(self, name, doc):
        self.name, self.doc = name, doc
        self.hoist = Hoister()
        self.funcs = []      # (prototype, doc, body lines)
        self.macros = []
        self.decls = []      # extra header lines (declarations of data)
        self.data = []       # extra C lines (constant tables)
        self.trig = None     # substitution sin/cos(head angle) -> sc[] inputs

    def function(self, proto, doc, assigns, names, levels=(), prefix="x"):
        if self.trig:
            levels = [[(sy, x.subs(self.trig)) for sy, x in lev] for lev in levels]
            assigns = [(lhs, sp.sympify(x).subs(self.trig)) for lhs, x in assigns]
            assert not any(x.has(sp.sin, sp.cos) for lev in levels for _, x in lev)
        levels = prune(levels, [x for _, x in assigns])
        hl = [[(sy, self.hoist(x)) for sy, x in lev] for lev in levels]
        hoisted = [(lhs, self.hoist(x)) for lhs, x in assigns]
        pr = Printer({**names, **self.kmap()})
        lines0, flops0 = emit_levels(hl, pr)
        lines, flops = emit_block(hoisted, pr, prefix)
        flops += flops0
        self.funcs.append((proto, doc + " (%d flops)" % flops, lines0 + lines))
        return flops

    def kmap(self):
        return {s: "k[%d]" % i for i, (s, _) in enumerate(self.hoist.order)}

    def init_lines(self):
        pr = Printer(dict(PARAM_C))
        assigns = [("k[%d]" % i, e) for i, (s, e) in enumerate(self.hoist.order)]
        lines, flops = emit_block(assigns, pr, "c")
        return lines, flops


def stamp(sympy_version):
    return ("/* Generated by %s with SymPy %s - DO NOT EDIT.\n"
            " * Change the generator and rerun it: /usr/bin/python3 %s */\n"
            % (GENERATOR, sympy_version, GENERATOR))


def write_unit(unit, outdir):
    init_lines, init_flops = unit.init_lines()
    nk = len(unit.hoist.order)
    up = unit.name.upper()
    h = [stamp(sp.__version__), "/* %s */" % unit.doc,
         "#ifndef %s_H" % up, "#define %s_H" % up, "", '#include "hg_params.h"', "",
         "#define %s_NCONST %d  /* length of the constant table k[] */" % (up, nk)]
    h += unit.macros
    h += unit.decls
    h.append("")
    h.append("/* Fill k[%s_NCONST] with the parameter-only subexpressions (%d flops). */"
             % (up, init_flops))
    h.append("void %s_init(const hg_params *p, double *k);" % unit.name)
    for proto, doc, _ in unit.funcs:
        h.append("")
        h.append("/* %s */" % doc)
        h.append(proto + ";")
    h += ["", "#endif", ""]
    c = [stamp(sp.__version__), '#include "hg_math.h"  /* rtapi_math.h in realtime builds */',
         '#include "hg_errors.h"', '#include "hg_units.h"',
         '#include "%s.h"' % unit.name, ""]
    c += unit.data
    c.append("void %s_init(const hg_params *p, double *k)" % unit.name)
    c.append("{")
    c += init_lines
    c.append("}")
    for proto, doc, body in unit.funcs:
        c.append("")
        c.append("/* %s */" % doc)
        c.append(proto)
        c.append("{")
        c += body
        c.append("}")
    c.append("")
    for ext, text in (("h", h), ("c", c)):
        with open(os.path.join(outdir, "%s.%s" % (unit.name, ext)), "w") as f:
            f.write("\n".join(text))


def reduced_coordinates():
    z = sp.symbols("z0:6")
    c = sp.symbols("X Y Z A B C")
    zd = sp.symbols("zd0:6")
    cd = sp.symbols("Xd Yd Zd Ad Bd Cd")
    return sp.Matrix(z + c), sp.Matrix(zd + cd)


def gen_reduced(outdir):
    q, qd = reduced_coordinates()
    m = reduced_atomized(q, qd)
    M, Q, Jq, gamma = m["M"], m["Q"], m["Jq"], m["gamma"]
    u = Unit("hg_gen_reduced", "Bars lumped into exact point masses: q = [z(6), c(6)], "
             "c = X Y Z A B C.\n * Every function but init takes sc[6] = sin A, cos A, sin B, cos B, "
             "sin C, cos C of q[9..11].")
    u.trig, trig_names = trig_inputs(q[6:, 0])
    names = {**state_names(q, qd), **trig_names}
    Z, C = range(0, 6), range(6, 12)
    # M_zz is diagonal and constant; M_zc row k couples z_k with the head
    assigns = [("Mzz[%d]" % i, M[i, i]) for i in Z]
    assigns += matrix_assigns("Mzc", M, Z, C) + matrix_assigns("Mcc", M, C, C)
    assigns += [("Q[%d]" % i, Q[i]) for i in range(12)]
    assigns += [("Phi_z[%d]" % i, Jq[i, i]) for i in Z]
    assigns += matrix_assigns("Phi_c", Jq, range(6), C)
    assigns += [("gamma[%d]" % i, gamma[i]) for i in range(6)]
    for i in Z:
        for j in Z:
            assert i == j or M[i, j] == 0 and Jq[i, j] == 0
    fl_terms = u.function(
        "void hg_gen_reduced_terms(const double *k, const double q[12], const double qd[12],\n"
        "                          const double sc[6],\n"
        "                          double Mzz[6], double Mzc[36], double Mcc[36], double Q[12],\n"
        "                          double Phi_z[6], double Phi_c[36], double gamma[6])",
        "Mass matrix blocks (M_zz diagonal), Q = gravity - velocity terms, constraint "
        "Jacobian (Phi_z diagonal) and gamma = (Phi_q q')_q q'", assigns, names,
        levels=m["levels"])
    # the Reduced Cartesian kind's terms: A = -Phi_z^-1 Phi_c and
    # b = -Phi_z^-1 gamma formed here (Phi_z,k = c_k s_k: c_k cancelled
    # symbolically, one reciprocal of the atom s_k per carriage, A's Z
    # column exactly 1) instead of Phi_z, Phi_c, gamma
    pivc, pivs = zip(*[Jq[i, i].as_coeff_Mul() for i in Z])
    assert all(x.is_Symbol for x in pivs), pivs
    ipz = sp.symbols("ipz0:6")
    assigns = [("Mzz[%d]" % i, M[i, i]) for i in Z]
    assigns += matrix_assigns("Mzc", M, Z, C) + matrix_assigns("Mcc", M, C, C)
    assigns += [("Q[%d]" % i, Q[i]) for i in range(12)]
    for i in Z:
        for j in range(6):
            an = sp.expand(-Jq[i, 6 + j] / pivc[i])
            assigns.append(("A[%d]" % (6 * i + j), 1 if an == pivs[i] else an * ipz[i]))
    assigns += [("b[%d]" % i, -sp.expand(gamma[i] / pivc[i]) * ipz[i]) for i in Z]
    fl_cterms = u.function(
        "void hg_gen_cartesian_terms(const double *k, const double q[12], const double qd[12],\n"
        "                            const double sc[6],\n"
        "                            double Mzz[6], double Mzc[36], double Mcc[36], double Q[12],\n"
        "                            double A[36], double b[6])",
        "For the Reduced Cartesian kind: mass matrix blocks (M_zz diagonal), Q = gravity - "
        "velocity terms, A = -Phi_z^-1 Phi_c and b = -Phi_z^-1 gamma (z' = A c', "
        "z'' = A c'' + b)", assigns, names,
        levels=list(m["levels"]) + [[(ipz[i], 1 / pivs[i]) for i in Z]])
    mc = reduced_constraints_atomized(q)
    assigns = [("phi[%d]" % i, mc["phi"][i]) for i in range(6)]
    assigns += [("Phi_z[%d]" % i, mc["Jq"][i, i]) for i in Z]
    assigns += matrix_assigns("Phi_c", mc["Jq"], range(6), C)
    fl_con = u.function(
        "void hg_gen_reduced_constraints(const double *k, const double q[12], const double sc[6],\n"
        "                                double phi[6],\n"
        "                                double Phi_z[6], double Phi_c[36])",
        "Bar constraints |B-A|^2 - l^2 (m^2) and their Jacobian", assigns, names,
        levels=mc["levels"])
    ms = reduced_stabilize_atomized(q, qd)
    assigns = [("phi[%d]" % i, ms["phi"][i]) for i in range(6)]
    assigns += [("Phi_z[%d]" % i, ms["Phi_z"][i]) for i in Z]
    assigns += [("vc[%d]" % i, ms["vc"][i]) for i in Z]
    fl_stab = u.function(
        "void hg_gen_reduced_stabilize(const double *k, const double q[12], const double qd[12],\n"
        "                              const double sc[6],\n"
        "                              double phi[6], double Phi_z[6], double vc[6])",
        "For the Reduced Cartesian stabilization: phi, the diagonal Phi_z and "
        "vc = Phi_c c' (m^2/s)", assigns, names, levels=ms["levels"])
    fl_pot = u.function(
        "void hg_gen_reduced_potential(const double *k, const double q[12], const double sc[6],\n"
        "                              double *v)",
        "Gravity potential (J, up to a constant)", [("*v", m["V"])], names,
        levels=[[(sy, x) for sy, x in m["levels"][0] if str(sy).startswith("sw")]])
    u.q, u.qd = list(q), list(qd)
    fl_fused, fl_fused_acc = gen_fused(u, m, names)
    u.macros += ["#define HG_GEN_REDUCED_TERMS_FLOPS %d" % fl_terms,
                 "#define HG_GEN_CARTESIAN_TERMS_FLOPS %d" % fl_cterms,
                 "#define HG_GEN_REDUCED_CONSTRAINTS_FLOPS %d" % fl_con,
                 "#define HG_GEN_REDUCED_POTENTIAL_FLOPS %d" % fl_pot,
                 "#define HG_GEN_REDUCED_STABILIZE_FLOPS %d" % fl_stab,
                 "#define HG_GEN_FUSED_STEP_FLOPS %d" % fl_fused,
                 "#define HG_GEN_FUSED_ACCEL_FLOPS %d" % fl_fused_acc]
    write_unit(u, outdir)
    return m


def gen_fused(u, m, names):
    """Reduced Cartesian accelerations in one function: terms, A = -Phi_z^-1 Phi_c,
    the reduced 6x6 mass matrix and right-hand side (Eq. 13), an unrolled
    Cholesky solve and z'' = A c'' + b."""
    M, Q, Jq, gamma = m["M"], m["Q"], m["Jq"], m["gamma"]
    hoist = u.hoist
    prim = []
    sym = {}

    def S(name, expr):
        expr = sp.sympify(expr)
        if expr.is_Number or expr.free_symbols <= PARAMS:
            return expr         # structural zeros and constants stay literal
        s = sp.Symbol(name)
        prim.append((s, expr))
        sym[name] = s
        return s
    mzz = [S("mzz%d" % i, M[i, i]) for i in range(6)]
    mzc = [[S("mzc%d_%d" % (i, j), M[i, 6 + j]) for j in range(6)] for i in range(6)]
    mcc = [[S("mcc%d_%d" % (i, j), M[6 + i, 6 + j]) if j <= i else None for j in range(6)]
           for i in range(6)]
    for i in range(6):
        for j in range(i + 1, 6):
            mcc[i][j] = mcc[j][i]
    qz = [S("qz%d" % i, Q[i]) for i in range(6)]
    qc = [S("qc%d" % i, Q[6 + i]) for i in range(6)]
    # Phi_z is diagonal with Phi_z,k = c_k s_k (a number times an atom: 2 d_k,z),
    # so A_k = -Phi_c,k / Phi_z,k and b_k = -gamma_k / Phi_z,k are formed with
    # c_k cancelled symbolically: A_k,Z = 1 exactly, the rest one product by
    # 1/s_k each (bit-identical to dividing by Phi_z,k when c_k is a power of 2)
    pivc, pivs = zip(*[Jq[i, i].as_coeff_Mul() for i in range(6)])
    assert all(x.is_Symbol for x in pivs), pivs
    gm = [S("gm%d" % i, sp.expand(gamma[i] / pivc[i])) for i in range(6)]
    Anum = [[sp.expand(-Jq[i, 6 + j] / pivc[i]).subs(u.trig) for j in range(6)] for i in range(6)]
    levels = [[(sy, x.subs(u.trig)) for sy, x in lev] for lev in m["levels"]]
    prim = [(sy, sp.sympify(x).subs(u.trig)) for sy, x in prim]
    levels = prune(levels, [x for _, x in prim] + [x for row in Anum for x in row])
    hl = [[(sy, hoist(x)) for sy, x in lev] for lev in levels]
    # primitives: hoisted + CSE'd; then the algebra on their symbols
    hp = [(s, hoist(x)) for s, x in prim]
    reps, red = sp.cse([x for _, x in hp], symbols=sp.numbered_symbols("x"),
                       optimizations="basic")
    seq = []
    for li, lev in enumerate(hl):
        lreps, lred = sp.cse([x for _, x in lev], symbols=sp.numbered_symbols("u%d_" % li),
                             optimizations="basic")
        seq += list(lreps) + [(sy, x) for (sy, _), x in zip(lev, lred)]
    seq += list(reps) + [(s, x) for (s, _), x in zip(hp, red)]
    fz = sp.symbols("fz0:6")

    def T(name, expr):
        expr = sp.sympify(expr)
        if expr.is_Number or expr.free_symbols <= PARAMS:
            return expr         # constants stay symbolic until used (hoisted there)
        expr = hoist(expr)
        s = sp.Symbol(name)
        seq.append((s, expr))
        return s
    ipz = [T("ipz%d" % i, 1 / pivs[i]) for i in range(6)]
    A = [[T("A%d_%d" % (i, j), 1 if Anum[i][j] == pivs[i] else Anum[i][j] * ipz[i])
          for j in range(6)] for i in range(6)]
    b = [T("b%d" % i, -gm[i] * ipz[i]) for i in range(6)]
    fq = [T("fq%d" % i, qz[i] + fz[i]) for i in range(6)]
    # Eq. 13's M_cc + M_cz A + A^T M_zc + A^T M_zz A with M_zz = m_z I (a
    # parameter-only scalar, checked) as one Gram matrix plus a sparse
    # correction: with G = A + M_zc / m_z,
    #   M_hat = M_cc - M_cz M_zc / m_z + m_z G^T G
    # (M_zc has two state-dependent columns and one constant one: G's
    # Z column is constant, the correction a 3x3 block); the right-hand
    # side Q_c + A^T (Q_z + f_z) - (M_cz + A^T M_zz) b likewise as
    #   Q_c + A^T (Q_z + f_z - m_z b) - M_cz b.
    mz = mzz[0]
    assert all(x == mz for x in mzz) and mz.free_symbols <= PARAMS, mzz
    G = [[T("g%d_%d" % (kk, i), A[kk][i] + mzc[kk][i] / mz) for i in range(6)] for kk in range(6)]
    Mh = [[None] * 6 for _ in range(6)]
    for i in range(6):
        for j in range(i + 1):
            e = mcc[i][j] - sum(mzc[kk][i] * mzc[kk][j] for kk in range(6)) / mz \
                + mz * sp.factor_terms(sum(G[kk][i] * G[kk][j] for kk in range(6)))
            Mh[i][j] = T("mh%d_%d" % (i, j), e)
    h = [T("h%d" % kk, fq[kk] - mz * b[kk]) for kk in range(6)]
    rhs = [T("r%d" % i, qc[i] + sum(A[kk][i] * h[kk] - mzc[kk][i] * b[kk] for kk in range(6)))
           for i in range(6)]
    # unrolled LDL^T (M = L D L^T, unit L, reciprocal pivots: no square
    # roots); pivot checks inserted by the printer
    L = [[None] * 6 for _ in range(6)]
    E = [[None] * 6 for _ in range(6)]     # E[i][k] = L[i][k] D[k]
    iD = [None] * 6
    checks = []
    for j in range(6):
        dj = T("d%d" % j, Mh[j][j] - sum(L[j][kk] * E[j][kk] for kk in range(j)))
        checks.append(dj)
        iD[j] = T("id%d" % j, 1 / dj)
        for i in range(j + 1, 6):
            E[i][j] = T("ld%d_%d" % (i, j), Mh[i][j] - sum(L[i][kk] * E[j][kk] for kk in range(j)))
            L[i][j] = T("l%d_%d" % (i, j), E[i][j] * iD[j])
    y = [None] * 6
    for i in range(6):
        y[i] = T("y%d" % i, rhs[i] - sum(L[i][kk] * y[kk] for kk in range(i)))
    x = [None] * 6
    for i in reversed(range(6)):
        x[i] = T("cdd%d" % i, y[i] * iD[i] - sum(L[kk][i] * x[kk] for kk in range(i + 1, 6)))
    qdd_s = [T("zdd%d" % i, b[i] + sum(A[i][j] * x[j] for j in range(6))) for i in range(6)] + x
    # the accelerations alone: one stage of a higher-order scheme
    seq_acc = list(seq)
    # the rest of the step: improved Euler on the full state ...
    q, qd = u.q, u.qd
    dt = sp.Symbol("dt")
    q1 = [T("q1_%d" % i, q[i] + qd[i] * dt + qdd_s[i] * dt * dt / 2) for i in range(12)]
    # (z' of the prediction is not needed: the projection replaces it)
    qd1 = [None] * 6 + [T("qd1_%d" % i, qd[i] + qdd_s[i] * dt) for i in range(6, 12)]
    # ... sin/cos of the new head angles (returned for the next step) ...
    for i in range(3):
        seq.append((None, "sc1[%d] = sin(%s);" % (2 * i, q1[9 + i].name)))
        seq.append((None, "sc1[%d] = cos(%s);" % (2 * i + 1, q1[9 + i].name)))
    # ... one Newton step on z and the velocity projection z' = A c' at
    # the predicted state (the atoms of reduced_stabilize_atomized there)
    ms = reduced_stabilize_atomized(sp.Matrix(q), sp.Matrix(qd))
    sc1 = sp.symbols("s1A c1A s1B c1B s1C c1C")
    at = {}
    for lev in ms["levels"]:
        for sy, _ in lev:
            at[sy] = sp.Symbol("s_" + sy.name)
    to_new = {**{a: b for a, b in zip(TRIG_SYMS, sc1)}, **{a: b for a, b in zip(q, q1)},
              **{a: b for a, b in zip(qd[6:], qd1[6:])}, **at}

    def moved(e):
        return sp.sympify(e).subs(u.trig).subs(to_new, simultaneous=True)
    slevels = [[(at[sy], moved(x)) for sy, x in lev] for lev in ms["levels"]]
    outs_s = [moved(e) for e in list(ms["phi"]) + list(ms["Phi_z"]) + list(ms["vc"])]
    slevels = prune(slevels, outs_s)
    for li, lev in enumerate(slevels):
        hx = [hoist(x) for _, x in lev]
        lreps, lred = sp.cse(hx, symbols=sp.numbered_symbols("cs%d_" % li), optimizations="basic")
        seq += list(lreps) + [(sy, x) for (sy, _), x in zip(lev, lred)]
    phi1, pz1, vc1 = outs_s[:6], outs_s[6:12], outs_s[12:]
    # Phi_z,k = c_k s_k again: one division by the atom s_k, c_k folded in
    pz1c, pz1s = zip(*[x.as_coeff_Mul() for x in pz1])
    ipz1 = [T("ipz1_%d" % k, 1 / pz1s[k]) for k in range(6)]
    dl = [T("dl%d" % k, phi1[k] * ipz1[k] / pz1c[k]) for k in range(6)]
    rl = hoist(1 / (2 * P["l"]))
    outs = [("qdd[%d]" % i, qdd_s[i]) for i in range(12)]
    outs += [("q1[%d]" % k, q1[k] - dl[k]) for k in range(6)]
    outs += [("q1[%d]" % i, q1[i]) for i in range(6, 12)]
    outs += [("qd1[%d]" % k, (-vc1[k] / pz1c[k]) * ipz1[k]) for k in range(6)]
    outs += [("qd1[%d]" % i, qd1[i]) for i in range(6, 12)]
    pr = Printer({**names, **u.kmap(), **{s: "fz[%d]" % i for i, s in enumerate(fz)},
                  **{s: "sc1[%d]" % i for i, s in enumerate(sc1)}})

    def emit(sequence, outputs):
        """C lines and flops of a straight-line sequence and its outputs."""
        ls, fl = [], 0
        for s, e in sequence:
            if s is None:
                ls.append("    " + e)
                continue
            ls.append("    const double %s = %s;" % (s.name, pr.doprint(e)))
            fl += count_flops([e])
            if s in checks:
                ls.append("    if (!(%s > 0.0)) return HG_ERR_SINGULAR_MASS;" % s.name)
        for lhs, e in outputs:
            ls.append("    %s = %s;" % (lhs, pr.doprint(e)))
            fl += count_flops([e])
        return ls, fl
    lines_acc, flops_acc = emit(seq_acc, [("qdd[%d]" % i, qdd_s[i]) for i in range(12)])
    lines_acc.append("    return 0;")
    u.funcs.append((
        "int hg_gen_fused_accel(const double *k, const double q[12], const double qd[12],\n"
        "                       const double sc[6], const double fz[6], double qdd[12])",
        "The Reduced Cartesian accelerations in one function (the first part of "
        "hg_gen_fused_step, for the stages of higher-order schemes): with carriage forces "
        "fz, qdd = [z'', c''] (Eq. 13, c independent, unrolled LDL^T). 0 or "
        "HG_ERR_SINGULAR_MASS (%d flops)" % flops_acc,
        lines_acc))
    lines, flops = emit(seq, outs)
    # largest bar-length error after the Newton step: Phi is quadratic in
    # z_k, so bar k is left with delta_k^2 (m^2), i.e. delta_k^2 / (2 l) (m)
    # (straight-line: the largest delta_k^2, times 1/(2 l) once, which
    # rounding preserves as the largest of delta_k^2 / (2 l))
    lines.append("    {")
    lines.append("        double worst = 0.0, e;")
    for d in dl:
        lines.append("        e = %s*%s;" % (d.name, d.name))
        lines.append("        if (!(e <= worst))")
        lines.append("            worst = e;")
    lines.append("        *residual_m = worst*%s;" % pr.doprint(rl))
    lines.append("    }")
    flops += 13
    lines.append("    return 0;")
    u.funcs.append((
        "int hg_gen_fused_step(const double *k, const double q[12], const double qd[12],\n"
        "                      const double sc[6], const double fz[6], double dt,\n"
        "                      double q1[12], double qd1[12], double qdd[12], double sc1[6],\n"
        "                      double *residual_m)",
        "The whole Reduced Cartesian step in one function (the paper's future work): "
        "with carriage forces fz, the accelerations qdd = [z'', c''] (Eq. 13, c "
        "independent, unrolled LDL^T), improved Euler over dt, one Newton step on z "
        "and z' = A c' at the predicted state; sc1 = sin/cos of q1's head angles, "
        "residual_m the largest bar-length error left (m). 0 or HG_ERR_SINGULAR_MASS "
        "(%d flops, sin/cos not counted)" % flops,
        lines))
    return flops, flops_acc


def gen_standard(outdir):
    m = standard_model()
    q, qd, M, Q, phi, Jq, gamma = m["q"], m["qd"], m["M"], m["Q"], m["phi"], m["Jq"], m["gamma"]
    u = Unit("hg_gen_standard", "Bars as rigid bodies: q = [z(6), a(12), c(6)], "
             "a = (phi_k, theta_k) per bar, u_k = Rx(phi) Ry(theta) (0,0,-1).")
    names = state_names(q, qd)
    Z, Aa, C = range(0, 6), range(6, 18), range(18, 24)
    # structure: z_k couples only with its own bar angles; bars do not couple
    for i in Z:
        for j in range(24):
            if j != i and j not in (6 + 2 * i, 7 + 2 * i):
                assert M[i, j] == 0
    for i in Aa:
        own = (6 + 2 * ((i - 6) // 2), 7 + 2 * ((i - 6) // 2))
        for j in list(Aa) + list(C):
            if j not in own:
                assert M[i, j] == 0, (i, j)
    for r in range(18):
        for j in Z:
            assert Jq[r, j] == (1 if (r % 3 == 2 and r // 3 == j) else 0)
        for j in Aa:
            if (j - 6) // 2 != r // 3:
                assert Jq[r, j] == 0
    assigns = [("Mzz[%d]" % i, M[i, i]) for i in Z]
    assigns += [("Mza[%d]" % (2 * i + s), M[i, 6 + 2 * i + s]) for i in Z for s in range(2)]
    assigns += [("Maa[%d]" % (4 * kk + 2 * r + s), M[6 + 2 * kk + r, 6 + 2 * kk + s])
                for kk in range(6) for r in range(2) for s in range(2)]
    assigns += matrix_assigns("Mcc", M, C, C)
    assigns += [("Q[%d]" % i, Q[i]) for i in range(24)]
    assigns += [("Phi_a[%d]" % (6 * kk + 2 * r + s), Jq[3 * kk + r, 6 + 2 * kk + s])
                for kk in range(6) for r in range(3) for s in range(2)]
    assigns += matrix_assigns("Phi_c", Jq, range(18), C)
    assigns += [("gamma[%d]" % i, gamma[i]) for i in range(18)]
    fl_terms = u.function(
        "void hg_gen_standard_terms(const double *k, const double q[24], const double qd[24],\n"
        "                           double Mzz[6], double Mza[12], double Maa[24], double Mcc[36],\n"
        "                           double Q[24], double Phi_a[36], double Phi_c[108],\n"
        "                           double gamma[18])",
        "Mass matrix blocks (M_zz diagonal, Mza[2k+s] = M(z_k, a_2k+s), Maa 2x2 per bar), "
        "Q = gravity - velocity terms, constraint Jacobian blocks (Phi_a 3x2 per bar, "
        "Phi_c 18x6; Phi_z is constant: row 3k+2 has 1 at z_k) and gamma", assigns, names)
    assigns = [("phi[%d]" % i, phi[i]) for i in range(18)]
    assigns += [("Phi_a[%d]" % (6 * kk + 2 * r + s), Jq[3 * kk + r, 6 + 2 * kk + s])
                for kk in range(6) for r in range(3) for s in range(2)]
    assigns += matrix_assigns("Phi_c", Jq, range(18), C)
    fl_con = u.function(
        "void hg_gen_standard_constraints(const double *k, const double q[24], double phi[18],\n"
        "                                 double Phi_a[36], double Phi_c[108])",
        "Bar-end constraints B + l u - A (m) and their Jacobian blocks", assigns, names)
    fl_pot = u.function(
        "void hg_gen_standard_potential(const double *k, const double q[24], double *v)",
        "Gravity potential (J, up to a constant)",
        [("*v", m["V"])], names)
    u.macros += ["#define HG_GEN_STANDARD_TERMS_FLOPS %d" % fl_terms,
                 "#define HG_GEN_STANDARD_CONSTRAINTS_FLOPS %d" % fl_con,
                 "#define HG_GEN_STANDARD_POTENTIAL_FLOPS %d" % fl_pot]
    write_unit(u, outdir)
    return m


# ---------------------------------------------------------------------------
# identification: the same reduced model, linear in its inertial parameters
# (docs/identification.md). Each body is written with the parameters that
# its kinetic and potential energy are linear in: the head by its mass, its
# first moment and its inertia about Op (head axes), the bars by their
# lumped masses, each carriage by its inertial mass (carriage plus reflected
# rotor). The carriages' own weight is constant per carriage and is left to
# the per-drive offset column (src/hg_regressor.c), as are friction.
REG_PARAMS = [
    ("m_head", "kg", "head mass"),
    ("m_head*com_x", "kg m", "head first moment about Op, head x (spec: 0)"),
    ("m_head*com_y", "kg m", "head first moment about Op, head y (spec: 0)"),
    ("m_head*com_z", "kg m", "head first moment about Op, head z (spec: -m_head*head_com)"),
    ("j_head_xx", "kg m^2", "head inertia about Op, head axes (spec: i_head_xx + m_head*head_com^2)"),
    ("j_head_yy", "kg m^2", "head inertia about Op, head axes (spec: i_head_yy + m_head*head_com^2)"),
    ("j_head_zz", "kg m^2", "head inertia about Op, head axes (spec: i_head_zz)"),
    ("j_head_xy", "kg m^2", "head inertia about Op, tensor element xy (spec: 0)"),
    ("j_head_xz", "kg m^2", "head inertia about Op, tensor element xz (spec: 0)"),
    ("j_head_yz", "kg m^2", "head inertia about Op, tensor element yz (spec: 0)"),
    ("m_end", "kg", "lumped bar mass at each joint (spec: 2 i_bar/l^2 - m_bar/2)"),
    ("m_mid", "kg", "lumped bar mass at mid-length (spec: 2 m_bar - 4 i_bar/l^2)"),
] + [("m_drive[%d]" % k, "kg", "carriage %d inertial mass: m_carriage + j_rotor (2 pi/lead)^2" % k)
     for k in range(6)]


def regressor_model():
    """Inverse dynamics r = M q'' - Q of the reduced model (as reduced_model(),
    flat) with the parameters of REG_PARAMS as symbols, and its Jacobian
    Y = dr/dpi (12 x len(REG_PARAMS)): r = Y pi exactly, since r is linear in pi."""
    q, qd = reduced_coordinates()
    qdd = sp.Matrix(sp.symbols("zdd0:6") + sp.symbols("Xdd Ydd Zdd Add Bdd Cdd"))
    z, c, cd = q[:6, 0], q[6:, 0], qd[6:, 0]
    pi = sp.symbols("pi0:%d" % len(REG_PARAMS))
    mh, hv = pi[0], sp.Matrix(pi[1:4])
    J = sp.Matrix([[pi[4], pi[7], pi[8]], [pi[7], pi[5], pi[9]], [pi[8], pi[9], pi[6]]])
    me, mm, mdrive = pi[10], pi[11], pi[12:18]
    R = head_rotation(c)
    Pp = sp.Matrix(c[:3])
    sysm = System(q, qd)
    # head about Op: T = 1/2 m |P'|^2 + P'.(R h)' + 1/2 wb^T J wb
    sysm.point(mh, Pp)
    sysm.pair(1, Pp, R * hv)
    sysm.rotation(R, c[3:], cd[3:], J)
    sysm.weight(mh, Pp)
    sysm.weight(1, R * hv)
    for k in range(6):
        B = post_point(k, P["lb"]) + sp.Matrix([0, 0, P["h"] + z[k]])
        A = Pp + R * post_point(k, P["lp"])
        sysm.point(mdrive[k], B)          # carriage + rotor: inertia; weight in the offset
        for mass, pos in ((me, A), (me, B), (mm, (A + B) / 2)):
            sysm.point(mass, pos)
            sysm.weight(mass, pos)
    sysm.finish()
    r = sysm.M * qdd - sysm.Q
    Y = r.jacobian(sp.Matrix(pi))
    assert all(sp.expand(x).free_symbols.isdisjoint(pi) for x in Y)
    return dict(q=q, qd=qd, qdd=qdd, pi=pi, Y=Y, r=r)


def reg_pi_spec():
    """The spec's values of REG_PARAMS as expressions of hg_params (for the
    generated hg_gen_regressor_spec, which the unit test checks the regressor
    against the dynamics with)."""
    me, mm = derived_masses()
    m_rot = P["j_rotor"] * (2 * sp.pi / P["lead"]) ** 2
    hc2 = P["m_head"] * P["head_com"] ** 2
    return [P["m_head"], 0, 0, -P["m_head"] * P["head_com"],
            P["i_head_xx"] + hc2, P["i_head_yy"] + hc2, P["i_head_zz"], 0, 0, 0,
            me, mm] + [P["m_carriage"] + m_rot] * 6


def gen_regressor(outdir):
    m = regressor_model()
    q, qd, qdd, Y = m["q"], m["qd"], m["qdd"], m["Y"]
    n = len(REG_PARAMS)
    u = Unit("hg_gen_regressor", "Identification: the reduced model's inverse dynamics "
             "r = M q'' - Q, linear in its inertial parameters\n * (hg_gen_regressor_names): "
             "r = Y pi, rows z (6) and c (6). Depends on the geometry and g only.\n"
             " * Every function but init takes sc[6] = sin A, cos A, sin B, cos B, sin C, cos C of q[9..11].")
    u.trig, trig_names = trig_inputs(q[6:, 0])
    names = {**state_names(q, qd), **trig_names, **{s: "qdd[%d]" % i for i, s in enumerate(qdd)}}
    assigns = [("Yz[%d]" % (i * n + j), Y[i, j]) for i in range(6) for j in range(n)]
    assigns += [("Yc[%d]" % (i * n + j), Y[6 + i, j]) for i in range(6) for j in range(n)]
    fl = u.function(
        "void hg_gen_regressor(const double *k, const double q[12], const double qd[12],\n"
        "                      const double qdd[12], const double sc[6],\n"
        "                      double Yz[6 * HG_GEN_REGRESSOR_NPAR], double Yc[6 * HG_GEN_REGRESSOR_NPAR])",
        "Regressor of M q'' - Q at a consistent state (q, q', q''): row i of Yz (carriage z_i) "
        "and of Yc (head coordinate i of X Y Z A B C), column j the parameter "
        "hg_gen_regressor_names[j], row-major", assigns, names)
    body = u.funcs[-1][2]
    if not any("q[" in x.replace("qd[", "").replace("qdd[", "") for x in body):
        body.insert(0, "    (void)q;    /* positions enter through the head angles' sc only */")
    spec = reg_pi_spec()
    pr = Printer(dict(PARAM_C))
    body = ["    pi[%d] = %s;" % (j, pr.doprint(sp.sympify(x))) for j, x in enumerate(spec)]
    u.funcs.append(("void hg_gen_regressor_spec(const hg_params *p, double pi[HG_GEN_REGRESSOR_NPAR])",
                    "The parameters of hg_gen_regressor_names that the spec's set p describes "
                    "(the lumped bar of docs/model.md, the rotor reflected by the lead)", body))
    u.macros += ["#define HG_GEN_REGRESSOR_NPAR %d  /* columns of hg_gen_regressor */" % n,
                 "#define HG_GEN_REGRESSOR_FLOPS %d" % fl]
    u.decls += ["", "/* Name, SI unit and meaning of each column (REG_PARAMS of the generator). */",
                "extern const char *const hg_gen_regressor_names[HG_GEN_REGRESSOR_NPAR];",
                "extern const char *const hg_gen_regressor_units[HG_GEN_REGRESSOR_NPAR];",
                "extern const char *const hg_gen_regressor_what[HG_GEN_REGRESSOR_NPAR];"]
    for tab, idx in (("names", 0), ("units", 1), ("what", 2)):
        u.data.append("const char *const hg_gen_regressor_%s[HG_GEN_REGRESSOR_NPAR] = {" % tab)
        u.data += ['    "%s",' % r[idx] for r in REG_PARAMS]
        u.data += ["};", ""]
    write_unit(u, outdir)
    return m


def main(argv):
    if sp.__version__ != REQUIRED_SYMPY:
        sys.stderr.write("gen_dynamics.py: SymPy %s found, %s required (Debian 12 "
                         "python3-sympy); refusing to generate.\n"
                         % (sp.__version__, REQUIRED_SYMPY))
        return 2
    outdir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "src", "generated")
    args = list(argv)
    which = ["reduced", "standard", "regressor"]
    while args:
        a = args.pop(0)
        if a == "--out" and args:
            outdir = args.pop(0)
        elif a == "--only" and args:
            which = args.pop(0).split(",")
        else:
            sys.stderr.write("usage: gen_dynamics.py [--out DIR] [--only reduced,standard,regressor]\n")
            return 2
    os.makedirs(outdir, exist_ok=True)
    if "reduced" in which:
        gen_reduced(outdir)
    if "standard" in which:
        gen_standard(outdir)
    if "regressor" in which:
        gen_regressor(outdir)
    return 0


if __name__ == "__main__":
    # deterministic output: set iteration order must not depend on the hash seed
    if os.environ.get("PYTHONHASHSEED") != "0":
        os.environ["PYTHONHASHSEED"] = "0"
        os.execv(sys.executable, [sys.executable] + sys.argv)
    sys.exit(main(sys.argv[1:]))
