#!/usr/bin/python3
"""fmu_pid_example.py - co-simulate build/hexaglide.fmu with LinuxCNC's PID
law and plot a move (docs/fmu.md).

The FMU is loaded through ctypes on its FMI 3.0 C API (no FMI library):
unzipped, its binary opened, its variables found by name in its
modelDescription.xml. Six PIDs, ported expression by expression from
src/hg_pid.c (LinuxCNC's pid component), close the loops in the servo
thread's order: read the encoder positions, pid.N.do-pid-calcs, write the
DAC volts, one fmi3DoStep of one servo period. Gains and scales come from
the [JOINT_N] sections of a LinuxCNC INI file.

    tools/fmu_pid_example.py [--fmu build/hexaglide.fmu] [--ini configs/hexaglide.ini]
                             [--pose X,Y,Z,A,B,C] [--time S] [--csv FILE] [--plot FILE]

The move: the joints go from HOME to those of --pose (mm, degrees; through
`build/hexaglide ik`) with a quintic time law in --time seconds, then hold
for 0.3 s. Prints the peak following error of each joint; --plot writes
the commanded and actual joints and the following errors (matplotlib).
Needs Python 3 with numpy (and matplotlib for --plot)."""
import argparse
import ctypes as C
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
import zipfile

import numpy as np

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
JOINTS = 6

# ---- the FMI 3.0 co-simulation API through ctypes ----
fmi3Status = C.c_int
LOGGER = C.CFUNCTYPE(None, C.c_void_p, fmi3Status, C.c_char_p, C.c_char_p)
STATUS = ["OK", "Warning", "Discard", "Error", "Fatal"]


class FMU:
    """One instance of a co-simulation FMU: values by variable name, one step at a time."""

    def __init__(self, path, name="pid-example"):
        self.dir = tempfile.mkdtemp(prefix="fmu-")
        with zipfile.ZipFile(path) as z:
            z.extractall(self.dir)
        md = ET.parse(os.path.join(self.dir, "modelDescription.xml")).getroot()
        ident = md.find("CoSimulation").get("modelIdentifier")
        self.vr = {v.get("name"): int(v.get("valueReference")) for v in md.find("ModelVariables")}
        self.lib = C.CDLL(os.path.join(self.dir, "binaries", "x86_64-linux", ident + ".so"))
        self.messages = []
        self._log = LOGGER(lambda env, status, cat, msg: self.messages.append(
            "[%s] %s" % (STATUS[status] if 0 <= status < 5 else status, msg.decode())))
        f = self.lib
        f.fmi3InstantiateCoSimulation.restype = C.c_void_p
        f.fmi3InstantiateCoSimulation.argtypes = [C.c_char_p, C.c_char_p, C.c_char_p, C.c_bool, C.c_bool, C.c_bool,
                                                  C.c_bool, C.c_void_p, C.c_size_t, C.c_void_p, LOGGER, C.c_void_p]
        for fn in ("fmi3SetFloat64", "fmi3GetFloat64"):
            getattr(f, fn).argtypes = [C.c_void_p, C.POINTER(C.c_uint32), C.c_size_t, C.POINTER(C.c_double),
                                       C.c_size_t]
        f.fmi3EnterInitializationMode.argtypes = [C.c_void_p, C.c_bool, C.c_double, C.c_double, C.c_bool, C.c_double]
        f.fmi3ExitInitializationMode.argtypes = [C.c_void_p]
        f.fmi3DoStep.argtypes = [C.c_void_p, C.c_double, C.c_double, C.c_bool, C.POINTER(C.c_bool),
                                 C.POINTER(C.c_bool), C.POINTER(C.c_bool), C.POINTER(C.c_double)]
        f.fmi3Terminate.argtypes = [C.c_void_p]
        f.fmi3FreeInstance.argtypes = [C.c_void_p]
        self.s = f.fmi3InstantiateCoSimulation(name.encode(), md.get("instantiationToken").encode(), b"", False,
                                               False, False, False, None, 0, None, self._log, None)
        if not self.s:
            raise RuntimeError("fmi3InstantiateCoSimulation failed: %s" % "; ".join(self.messages))
        # without loggingOn the FMU logs errors only (FMI 3.0): the machine's faults too, not its events
        f.fmi3SetDebugLogging.argtypes = [C.c_void_p, C.c_bool, C.c_size_t, C.POINTER(C.c_char_p)]
        f.fmi3SetDebugLogging(self.s, True, 2, (C.c_char_p * 2)(b"logStatusError", b"logStatusWarning"))
        self.t = 0.0
        self._flags = [C.c_bool(), C.c_bool(), C.c_bool()]
        self._last = C.c_double()

    def _call(self, rc, what):
        if rc not in (0, 1):
            raise RuntimeError("%s returned %s: %s" % (what, STATUS[rc] if 0 <= rc < 5 else rc,
                                                       "; ".join(self.messages[-6:])))
        return rc

    def set(self, names, values):
        """fmi3SetFloat64 of the named variables."""
        n = len(names)
        vr = (C.c_uint32 * n)(*[self.vr[x] for x in names])
        self._call(self.lib.fmi3SetFloat64(self.s, vr, n, (C.c_double * n)(*values), n), "fmi3SetFloat64")

    def get(self, names):
        """fmi3GetFloat64 of the named variables, as a list."""
        n = len(names)
        vr, out = (C.c_uint32 * n)(*[self.vr[x] for x in names]), (C.c_double * n)()
        self._call(self.lib.fmi3GetFloat64(self.s, vr, n, out, n), "fmi3GetFloat64")
        return list(out)

    def initialize(self):
        """Initialization Mode in and out: the parameters set so far are checked, the machine built at HOME."""
        self._call(self.lib.fmi3EnterInitializationMode(self.s, False, 0.0, 0.0, False, 0.0),
                   "fmi3EnterInitializationMode")
        self._call(self.lib.fmi3ExitInitializationMode(self.s), "fmi3ExitInitializationMode")

    def step(self, h):
        """One communication step of h seconds from the FMU's time."""
        rc = self._call(self.lib.fmi3DoStep(self.s, self.t, h, True, *[C.byref(x) for x in self._flags],
                                            C.byref(self._last)), "fmi3DoStep")
        self.t = self._last.value
        return rc

    def close(self):
        self.lib.fmi3Terminate(self.s)
        self.lib.fmi3FreeInstance(self.s)
        shutil.rmtree(self.dir, ignore_errors=True)


# ---- LinuxCNC's pid component, from src/hg_pid.c expression by expression ----
class Pid:
    """pid.N with the INI's gains (LinuxCNC's load-time values for the rest: Pgain 1, the others 0)."""
    KEYS = {"P": "pgain", "I": "igain", "D": "dgain", "BIAS": "bias", "FF0": "ff0", "FF1": "ff1", "FF2": "ff2",
            "FF3": "ff3", "DEADBAND": "deadband", "MAX_OUTPUT": "maxoutput", "MAX_ERROR_I": "maxerror_i"}

    def __init__(self, gains):
        self.pgain, self.igain, self.dgain, self.bias = 1.0, 0.0, 0.0, 0.0
        self.ff0 = self.ff1 = self.ff2 = self.ff3 = self.deadband = 0.0
        self.maxerror = self.maxerror_i = self.maxerror_d = 0.0
        self.maxcmd_d = self.maxcmd_dd = self.maxcmd_ddd = self.maxoutput = 0.0
        self.error_previous_target = 1
        for k, v in gains.items():
            if k in self.KEYS:
                setattr(self, self.KEYS[k], float(v))
        self.error_i = self.error_d = self.prev_error = self.prev_cmd = self.prev_fb = 0.0
        self.limit_state = self.cmd_d = self.cmd_dd = self.cmd_ddd = self.cmd_v = self.fb_v = 0.0
        self.prev_ie = 0
        self.error = self.output = 0.0

    @staticmethod
    def _limit(v, lim):
        if lim != 0.0:
            if v > lim:
                return lim
            if v < -lim:
                return -lim
        return v

    def calc(self, command, feedback, period_ns, enable=1, index_enable=0):
        """pid.N.do-pid-calcs: the output (V) for command and feedback (mm)."""
        periodfp = period_ns * 0.000000001
        periodrecip = 1.0 / periodfp
        ie_reset = self.prev_ie and not index_enable
        if not ie_reset and self.error_previous_target:
            tmp1 = self.prev_cmd - feedback
        else:
            tmp1 = command - feedback
        self.error = tmp1
        tmp1 = self._limit(tmp1, self.maxerror)
        if tmp1 > self.deadband:
            tmp1 -= self.deadband
        elif tmp1 < -self.deadband:
            tmp1 += self.deadband
        else:
            tmp1 = 0
        if enable != 0:
            if (tmp1 * self.limit_state) <= 0.0:
                self.error_i += tmp1 * periodfp
            self.error_i = self._limit(self.error_i, self.maxerror_i)
        else:
            self.error_i = 0
        if not ie_reset:
            self.cmd_v = (command - self.prev_cmd) * periodrecip
            self.fb_v = (feedback - self.prev_fb) * periodrecip
        self.error_d = self.cmd_v - self.fb_v
        self.prev_error = tmp1
        self.error_d = self._limit(self.error_d, self.maxerror_d)
        tmp2 = self.cmd_d
        self.cmd_d = self.cmd_v
        self.prev_ie = 1 if index_enable else 0
        self.prev_cmd = command
        self.prev_fb = feedback
        self.cmd_d = self._limit(self.cmd_d, self.maxcmd_d)
        tmp3 = self.cmd_dd
        self.cmd_dd = (self.cmd_d - tmp2) * periodrecip
        self.cmd_dd = self._limit(self.cmd_dd, self.maxcmd_dd)
        self.cmd_ddd = (self.cmd_dd - tmp3) * periodrecip
        self.cmd_ddd = self._limit(self.cmd_ddd, self.maxcmd_ddd)
        if enable != 0:
            tmp1 = self.bias + self.pgain * tmp1 + self.igain * self.error_i + self.dgain * self.error_d
            tmp1 += command * self.ff0 + self.cmd_d * self.ff1 + self.cmd_dd * self.ff2 + self.cmd_ddd * self.ff3
            if self.maxoutput != 0.0:
                if tmp1 > self.maxoutput:
                    tmp1 = self.maxoutput
                    self.limit_state = 1.0
                elif tmp1 < -self.maxoutput:
                    tmp1 = -self.maxoutput
                    self.limit_state = -1.0
                else:
                    self.limit_state = 0.0
        else:
            tmp1 = 0.0
            self.limit_state = 0.0
        self.output = tmp1
        return tmp1


# ---- the config and the move ----
def read_joints(ini):
    """[JOINT_0..5] of a LinuxCNC INI file: six {KEY: number}, read by build/hexaglide's INI reader
    (tools/hg_config.py: as soak and tune read them; a key given twice, a value that is no finite
    number or a key the HAL file sets missing is refused, naming key, file and line)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import hg_config
    try:
        return hg_config.read(ini, loop=True, cmd="fmu_pid_example", plant_option=None).joints
    except hg_config.ConfigError as ex:
        sys.exit("fmu_pid_example: %s" % ex)


def quintic_move(target_mm, seconds, hold, period):
    """Joint commands (n, 6): HOME to target with s(u) = 10u^3 - 15u^4 + 6u^5, then held."""
    n, m = int(round(seconds / period)), int(round(hold / period))
    u = np.arange(1, n + 1) / n
    s = 10 * u ** 3 - 15 * u ** 4 + 6 * u ** 5
    cmd = np.outer(s, np.asarray(target_mm, dtype=float))
    return np.vstack([cmd, np.tile(cmd[-1], (m, 1))])


def run(fmu_path, cmd_mm, joints, period_ns=1000000):
    """The closed loop: per period (feedback mm, f-error mm, pid output V) arrays (n, 6), and the FMU's messages."""
    fmu = FMU(fmu_path)
    try:
        fmu.set(["period", "enc_scale"], [period_ns * 1e-9, joints[0].get("INPUT_SCALE", 1.0)])
        if any(j.get("INPUT_SCALE", 1.0) != joints[0].get("INPUT_SCALE", 1.0) for j in joints):
            raise ValueError("the FMU has one enc_scale: give every joint the same INPUT_SCALE")
        fmu.initialize()
        pids = [Pid(j) for j in joints]
        pos = ["position_%d" % k for k in range(JOINTS)]
        dac = ["dac_%d" % k for k in range(JOINTS)]
        n = len(cmd_mm)
        fb, fe, out = np.zeros((n, JOINTS)), np.zeros((n, JOINTS)), np.zeros((n, JOINTS))
        prev = [0.0] * JOINTS
        for i in range(n):
            p = fmu.get(pos)                          # motenc.0.encoder-read
            volts = []
            for k in range(JOINTS):                   # motion's f-error, pid.k.do-pid-calcs
                fb[i, k], fe[i, k] = p[k], prev[k] - p[k]
                out[i, k] = pids[k].calc(float(cmd_mm[i][k]), p[k], period_ns)
                volts.append((out[i, k] - joints[k].get("OUTPUT_OFFSET", 0.0)) * joints[k].get("OUTPUT_SCALE", 1.0))
            fmu.set(dac, volts)                       # motenc.0.dac-write
            fmu.step(period_ns * 1e-9)                # motenc.0.dynamics: one servo period
            prev = [float(c) for c in cmd_mm[i]]
        return fb, fe, out, fmu.messages
    finally:
        fmu.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fmu", default=os.path.join(ROOT, "build", "hexaglide.fmu"))
    ap.add_argument("--ini", default=os.path.join(ROOT, "configs", "hexaglide.ini"))
    ap.add_argument("--pose", default="30,-20,-40,3,-2,5", help="target X,Y,Z (mm),A,B,C (deg)")
    ap.add_argument("--time", type=float, default=1.0, help="move time (s)")
    ap.add_argument("--csv", help="per period: t, cmd, fb, ferror, volts of each joint")
    ap.add_argument("--plot", help="PNG: commanded and actual joints, following errors")
    a = ap.parse_args()
    if not (a.time >= 0.01 and a.time <= 600):
        ap.error("--time %s: the move must take 0.01 to 600 s (not a number, or too short or long)" % a.time)
    for path, what in ((a.fmu, "make fmu"), (a.ini, "a LinuxCNC INI with [JOINT_0]..[JOINT_5]")):
        if not os.path.exists(path):
            sys.exit("fmu_pid_example: %s not found (%s)" % (path, what))
    ik = subprocess.run([os.path.join(ROOT, "build", "hexaglide"), "ik"] + a.pose.split(","),
                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if ik.returncode:
        sys.exit("fmu_pid_example: hexaglide ik %s: %s" % (a.pose, ik.stderr.strip() or "make host first"))
    target = [float(x) for x in ik.stdout.split()]
    joints = read_joints(a.ini)
    cmd = quintic_move(target, a.time, 0.3, 0.001)
    fb, fe, out, msgs = run(a.fmu, cmd, joints)
    for m in msgs:
        print(m)
    t = np.arange(1, len(cmd) + 1) * 0.001
    print("move to pose %s: joints %s mm in %g s, held 0.3 s" % (a.pose, " ".join("%.3f" % x for x in target), a.time))
    for k in range(JOINTS):
        print("joint %d: peak |f-error| %.4f mm, final %.2e mm, peak |output| %.3f V"
              % (k, np.max(np.abs(fe[:, k])), fe[-1, k], np.max(np.abs(out[:, k]))))
    if a.csv:
        cols = ["t_s"] + ["%s%d" % (c, k) for c in ("cmd_mm_", "fb_mm_", "ferror_mm_", "volts_") for k in range(6)]
        np.savetxt(a.csv, np.column_stack([t, cmd, fb, fe, out]), delimiter=",", header=",".join(cols),
                   comments="", fmt="%.17g")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
        for k in range(JOINTS):
            ax[0].plot(t, cmd[:, k], "--", color="C%d" % k, lw=1)
            ax[0].plot(t, fb[:, k], color="C%d" % k, lw=1, label="joint %d" % k)
            ax[1].plot(t, fe[:, k] * 1000, color="C%d" % k, lw=1, label="joint %d" % k)
        ax[0].set_ylabel("joint (mm): command dashed, encoder solid")
        ax[1].set_ylabel("following error (um)")
        ax[1].set_xlabel("t (s)")
        ax[0].legend(ncol=3, fontsize=8)
        ax[0].set_title("build/hexaglide.fmu with LinuxCNC's pid, gains of %s" % os.path.relpath(a.ini, ROOT))
        for x in ax:
            x.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=90)
        print("plot: %s" % a.plot)


if __name__ == "__main__":
    main()
