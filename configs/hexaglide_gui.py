#!/usr/bin/python3
"""hexaglide_gui.py - vismach 3D view of the Hexaglide (LinuxCNC vismach).

Shows the simulated machine, not the commanded one: carriage heights from
the virtual board's motenc-hexaglide.0.joint-N.pos and the head pose from
motenc-hexaglide.0.head-{x,y,z,a,b,c} (hexaglide_postgui.hal connects them).
Geometry in mm: L LB E LP on the command line (hexaglide_postgui.hal
passes the INI's [HEXAGLIDE] values, the ones both components get), else
the defaults of docs/model.md:
  guide ij on the vertical line through Rz(alpha_i) (lb, s_j e, 0)
  carriage joint B_ij = guide point + (0, 0, h + z_ij)
  head joint A_ij = P + Rz(C) Ry(B) Rx(A) Rz(alpha_i) (lp, s_j e, 0)
  bars of length l hang from the carriages to the head; the tool tip is
  tool_d below Op on the head axis.
"""
import math
import os
import sys
import tkinter

import hal
import numpy
import vismach
from vismach import (Box, BoxCentered, Capture, Collection, Color, CylinderZ,
                     HalRotate, HalTranslate, Rotate, Track, Translate, main)

L, LB, E, LP, TOOL_D = 1000.0, 484.0, 68.254, 73.085, 90.0
if len(sys.argv) == 5:
    L, LB, E, LP = (float(v) for v in sys.argv[1:])
H = math.sqrt(L * L - (LB - LP) ** 2)   # carriage height at HOME: follows from L, LB, LP
POSTS = (0.0, 120.0, -120.0)
SIGNS = (1.0, -1.0)



class Bar(Track):
    """vismach's Track, fixed for the 4x4 arrays glGetDoublev returns in 2.9."""

    def map_coords(self, tx, ty, tz, transform):
        return Track.map_coords(self, tx, ty, tz, numpy.asarray(transform).reshape(-1))


c = hal.component("hexaglide_gui")
for k in range(6):
    c.newpin("joint.%d" % k, hal.HAL_FLOAT, hal.HAL_IN)
for a in "xyzabc":
    c.newpin("head.%s" % a, hal.HAL_FLOAT, hal.HAL_IN)
c.ready()

world = Capture()
tool_tip = Capture()
work = Capture()

# --- head: a disc with the six universal joints and the spindle/tool
head_joints = []
head_caps = []
for i, alpha in enumerate(POSTS):
    for j, s in enumerate(SIGNS):
        cap = Capture()
        head_caps.append(cap)
        part = Collection([cap, Color([0.9, 0.6, 0.1, 1], [BoxCentered(16, 16, 16)])])
        part = Translate([part], LP, s * E, 0)
        head_joints.append(Rotate([part], alpha, 0, 0, 1))
disc = Color([0.5, 0.5, 0.6, 1], [CylinderZ(-15, LP + 30, 15, LP + 30)])
spindle = Color([0.7, 0.7, 0.7, 1], [CylinderZ(-TOOL_D + 30, 25, -15, 25)])
cutter = Color([1.0, 0.2, 0.2, 1], [CylinderZ(-TOOL_D, 3, -TOOL_D + 30, 3)])
tip = Translate([tool_tip], 0, 0, -TOOL_D)
head = Collection([disc, spindle, cutter, tip] + head_joints)
# R = Rz(C) Ry(B) Rx(A), then translate to P: innermost first
head = HalRotate([head], c, "head.a", 1, 1, 0, 0)
head = HalRotate([head], c, "head.b", 1, 0, 1, 0)
head = HalRotate([head], c, "head.c", 1, 0, 0, 1)
head = HalTranslate([head], c, "head.x", 1, 0, 0)
head = HalTranslate([head], c, "head.y", 0, 1, 0)
head = HalTranslate([head], c, "head.z", 0, 0, 1)

# --- posts with two guides each, carriages riding on them, bars
frame = []
carriages = []
bars = []
k = 0
for i, alpha in enumerate(POSTS):
    post = Color([0.35, 0.35, 0.4, 1], [Box(LB + 40, -E - 50, H - 320, LB + 90, E + 50, H + 320)])
    frame.append(Rotate([post], alpha, 0, 0, 1))
    for j, s in enumerate(SIGNS):
        guide = Color([0.8, 0.8, 0.85, 1], [Translate([CylinderZ(H - 300, 8, H + 300, 8)], LB + 25, s * E, 0)])
        frame.append(Rotate([guide], alpha, 0, 0, 1))
        cap = Capture()
        car = Collection([cap, Color([0.2, 0.5, 0.9, 1], [BoxCentered(50, 40, 60)])])
        car = HalTranslate([car], c, "joint.%d" % k, 0, 0, 1)
        car = Translate([car], LB, s * E, H)
        carriages.append(Rotate([car], alpha, 0, 0, 1))
        bar = Color([0.85, 0.85, 0.2, 1], [CylinderZ(0, 6, L, 6)])
        bars.append(Bar([bar], cap, head_caps[k], world))
        k += 1

# --- base plate and the workpiece (its top is where the logo is cut)
base = Color([0.3, 0.3, 0.3, 1], [CylinderZ(-300, LB + 120, -280, LB + 120)])
# the program cuts 1 mm deep with Op at Z-61: tool tip at Z-151
workpiece = Color([0.6, 0.45, 0.3, 1], [Box(-80, -80, -200, 80, 80, -60 - TOOL_D)])
workpiece = Collection([work, workpiece])

# vismach looks at the origin: lower the machine so its middle is there
model = Translate([Collection([world, base, workpiece, head] + frame + carriages + bars)],
                  0, 0, -450)


# vismach.main makes its own Tk root: give it a title and a place (top right,
# beside AXIS; HG_GUI_GEOMETRY overrides)
_tk = tkinter.Tk


def _placed_tk(*args, **kw):
    root = _tk(*args, **kw)
    root.title("Hexaglide 3D (simulated machine)")
    root.wm_geometry(os.environ.get("HG_GUI_GEOMETRY", "560x640-0+0"))
    return root


vismach.tkinter.Tk = _placed_tk
main(model, tool_tip, work, size=1300, lat=-72, lon=-30)
