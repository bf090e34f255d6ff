#!/usr/bin/python3
"""profile_stages.py - callgrind instruction counts of the board step by stage.

Reads a callgrind output file written with --separate-callers (each
function's cost split by its chain of callers) and uncompressed names
(--compress-strings=no --compress-pos=no), as bench/profile_step.sh writes
it, and prints instructions per servo period by stage: each function's own
instructions go to the stage of the outermost stage function on its chain
of callers below hg_step (drive, smooth forces, accelerations, friction,
stabilization, guard), the rest of hg_step to "step: other", the plant's
tool-path error (tool_error) to its own stage, and what else runs outside
hg_step to "board". Within a stage, to the innermost matching
part. Usage: profile_stages.py CALLGRIND_OUT PERIODS
"""
import re
import sys

# (stage, functions that start it): the outermost one on a chain wins
STAGES = [
    ("drive (windings)", ["hg_drive_step", "hg_drive_integral", "hg_drive_run", "hg_drive_channels"]),
    ("smooth forces (viscous, stops)", ["hg_carriage_forces"]),
    ("accelerations (2 Heun stages)", ["hg_cartesian_accel", "hg_fused_accel"]),
    ("friction", ["friction", "hg_integrate_friction"]),
    ("stabilization", ["hg_cartesian_stabilize"]),
    ("guard", ["hg_guard_check", "hg_guard_check_sc"]),
]
# (stage, part, functions or patterns): the innermost match on a chain wins
PARTS = {
    "drive (windings)": [("exp", [r"exp.*", r"__ieee754_exp.*", r"__exp.*"]),
                         ("ln (hg_drive_log)", [r"hg_drive_log.*"])],
    "accelerations (2 Heun stages)": [
        ("generated terms", ["hg_gen_cartesian_terms"]),
        ("head sin/cos (second stage)", ["hg_head_trig", r"__sin.*", r"__cos.*"]),
        ("LDL^T factor and solve", ["hg_spd6_factor", "hg_spd6_apply"]),
        ("mass data kept for friction", ["hg_mass_save_reduced"]),
        ("system assembly (Eq. 13)", ["cartesian_system"])],
    "friction": [
        ("solve (active sets, Stribeck)", ["hg_friction_solve"]),
        ("hold stuck carriages", ["hg_cartesian_hold"]),
        ("W (mass responses)", ["friction_general", "hg_mass_response_matrix"]),
        ("all-sliding shortcut", ["hg_friction_all_sliding"])],
    "stabilization": [
        ("head sin/cos", ["hg_head_trig", r"__sin.*", r"__cos.*"]),
        ("generated constraint terms", ["hg_gen_reduced_stabilize"])],
    "guard": [
        ("the memo's bounds alone (no joint points)", ["cones_clear", "pairs_clear", "head_moved"]),
        ("segment distances", ["hg_segment_distance"]),
        ("clearance bound (memo)", ["clearance", "end_moved"]),
        ("joint cosines, the cones' reference", ["joint_cosines", "cones_remember", "angle_of", r"acos.*",
                                                 r"__acos.*", r"__ieee754_acos.*"]),
        ("joint points", ["hg_joint_points", "hg_joint_points_rot", "head_offsets"]),
        ("rotation and its sin/cos", ["hg_rotation", "hg_rotation_sc", r"__sin.*", r"__cos.*"])],
}
REST = {"accelerations (2 Heun stages)": "solve, z'' = A c'' + b",
        "friction": "mass responses (the correction; W where not split out), rest",
        "stabilization": "Newton step on z, z' = A c'",
        "drive (windings)": "amplifiers, windings",
        "guard": "cone checks, the memo's bounds (inlined parts)"}


def matches(name, pats):
    return any(re.fullmatch(p, name) for p in pats)


def self_costs(path):
    """{caller chain (innermost first): own instructions}"""
    costs, fn, after_call = {}, None, False
    with open(path) as f:
        for line in f:
            if line.startswith("fn="):
                fn, after_call = tuple(line[3:].strip().split("'")), False
            elif line.startswith("calls="):
                after_call = True
            elif line[:1].isdigit() or line[:1] in "+-*":
                if after_call:            # the inclusive cost of a call: not this function's own
                    after_call = False
                    continue
                parts = line.split()
                if fn and len(parts) >= 2:
                    costs[fn] = costs.get(fn, 0) + int(parts[1])
    return costs


def classify(chain):
    names = [re.sub(r"\.(part|constprop|isra)\.\d+$", "", n) for n in chain]
    if "hg_step" not in names:
        if "tool_error" in names:          # the plant's forward solve of motion's commands
            return "tool-path error (forward kinematics of pos-cmd)", ""
        return "board (DAC, encoders, switches, ADC, latches)", ""
    below = names[:names.index("hg_step")]
    stage = None
    for n in reversed(below):             # outermost first
        for s, roots in STAGES:
            if n in roots:
                stage = s
                break
        if stage:
            break
    if not stage:
        return "step: other (copies, checks, stage sums)", ""
    for n in below:                       # innermost first
        for part, pats in PARTS.get(stage, []):
            if matches(n, pats):
                return stage, part
    return stage, REST.get(stage, "")


def main():
    costs, periods = self_costs(sys.argv[1]), int(sys.argv[2])
    total = sum(costs.values())
    stages, parts = {}, {}
    for chain, c in costs.items():
        s, p = classify(chain)
        stages[s] = stages.get(s, 0) + c
        if p:
            parts[(s, p)] = parts.get((s, p), 0) + c
    print("instructions per servo period (callgrind), %d periods: %.0f" % (periods, total / periods))
    print("%-52s %10s %7s" % ("stage / part", "instr", "share"))
    for s, c in sorted(stages.items(), key=lambda x: -x[1]):
        print("%-52s %10.0f %6.1f%%" % (s, c / periods, 100.0 * c / total))
        for (s2, p), c2 in sorted(parts.items(), key=lambda x: -x[1]):
            if s2 == s:
                print("  %-50s %10.0f %6.1f%%" % (p, c2 / periods, 100.0 * c2 / total))
    print("BENCH profile_board_step instr_per_period=%.0f" % (total / periods))


if __name__ == "__main__":
    main()
