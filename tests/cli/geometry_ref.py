"""geometry_ref.py - the Hexaglide's geometry written from docs/model.md
alone with numpy, for tests that need an answer independent of the C core
(tests/cli/test_working_volume, tests/linuxcnc/test_strike_saturate; not a
test itself): the inverse kinematics' closed form, the joint angles from the
bars' HOME directions, the closest distance of two bar axes as the minimum
of a convex quadratic over the unit square."""
import configparser

import numpy as np


def read_ini(path):
    cp = configparser.ConfigParser(strict=False, inline_comment_prefixes=("#",))
    cp.optionxform = str
    cp.read(path)
    box = [(float(cp["AXIS_" + a]["MIN_LIMIT"]), float(cp["AXIS_" + a]["MAX_LIMIT"])) for a in "XYZABC"]
    joints = [(float(cp["JOINT_%d" % k]["MIN_LIMIT"]), float(cp["JOINT_%d" % k]["MAX_LIMIT"])) for k in range(6)]
    geo = {k: float(v) for k, v in cp["HEXAGLIDE"].items() if k != "RECORD"}
    return box, joints, geo


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def rot(a, b, c):
    """R = Rz(C) Ry(B) Rx(A), angles in radians, for arrays of poses: (n, 3, 3)."""
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    return np.stack([np.stack([cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa], -1),
                     np.stack([sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa], -1),
                     np.stack([-sb, cb * sa, cb * ca], -1)], -2)


class Geometry:
    """docs/model.md: guides, head joints, h from L, LB, LP (SI inside)."""

    def __init__(self, g):
        self.l, lb, e, lp = g["L"] / 1e3, g["LB"] / 1e3, g["E"] / 1e3, g["LP"] / 1e3
        self.h = np.sqrt(self.l ** 2 - (lb - lp) ** 2)
        al = np.radians([0, 0, 120, 120, -120, -120])
        s = np.array([1, -1, 1, -1, 1, -1])
        self.guide = np.array([rz(al[k]) @ [lb, s[k] * e, 0] for k in range(6)])
        self.head = np.array([rz(al[k]) @ [lp, s[k] * e, 0] for k in range(6)])
        self.u0 = (self.head - self.guide - [0, 0, self.h]) / self.l
        self.cone_c, self.cone_h = np.radians(g["CONE_CARRIAGE"]), np.radians(g["CONE_HEAD"])
        self.d_bar = g["D_BAR"] / 1e3

    def state(self, poses_user):
        """Joints (mm), carriage and head joint angles (deg), bar ends for poses (n, 6) in mm, deg."""
        P = poses_user[:, :3] / 1e3
        R = rot(*np.radians(poses_user[:, 3:]).T)
        A = P[:, None, :] + np.einsum("nij,kj->nki", R, self.head)
        d = self.guide[None, :, :2] - A[:, :, :2]
        rad = self.l ** 2 - (d ** 2).sum(-1)
        z = A[:, :, 2] - self.h + np.sqrt(rad)
        B = np.broadcast_to(self.guide, A.shape).copy()
        B[:, :, 2] = self.h + z
        u = (A - B) / np.linalg.norm(A - B, axis=-1, keepdims=True)
        uh = np.einsum("nji,nkj->nki", R, u)          # R^T u: the bar in head axes
        ang_c = np.degrees(np.arccos(np.clip((u * self.u0).sum(-1), -1, 1)))
        ang_h = np.degrees(np.arccos(np.clip((uh * self.u0).sum(-1), -1, 1)))
        return z * 1e3, ang_c, ang_h, B, A


def point_segment(x, p, q):
    d = q - p
    t = np.clip(((x - p) * d).sum(-1) / (d * d).sum(-1), 0, 1)
    return np.linalg.norm(x - (p + t[..., None] * d), axis=-1)


def segment_distance(p1, q1, p2, q2):
    """Closest distance of segments, vectorized: the convex quadratic's
    stationary point when inside the unit square, else the edge minima."""
    d1, d2, w = q1 - p1, q2 - p2, p1 - p2
    a, b, c = (d1 * d1).sum(-1), (d1 * d2).sum(-1), (d2 * d2).sum(-1)
    dd, e = (d1 * w).sum(-1), (d2 * w).sum(-1)
    det = a * c - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (-dd * c + b * e) / det
        t = (a * e - b * dd) / det
    inside = (det > 1e-300) & (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)
    si, ti = np.where(inside, s, 0), np.where(inside, t, 0)
    interior = np.linalg.norm(w + si[..., None] * d1 - ti[..., None] * d2, axis=-1)
    best = np.minimum.reduce([point_segment(p1, p2, q2), point_segment(q1, p2, q2),
                              point_segment(p2, p1, q1), point_segment(q2, p1, q1)])
    return np.where(inside, np.minimum(best, interior), best)


