# hexaglide_axisrc.py - AXIS USER_COMMAND_FILE of configs/hexaglide.ini
# (executed by AXIS at startup, with AXIS's globals: c, s, root_window).
# With HG_AUTOSTART=1 in the environment (tools/run.sh's screenshot mode)
# AXIS does what an operator would: estop reset, machine on, home all
# joints, run the program given by [DISPLAY]OPEN_FILE. Otherwise: nothing.
import os

if os.environ.get("HG_AUTOSTART") == "1":
    _hg = {"step": 0}

    def _hg_autostart():
        s.poll()
        step = _hg["step"]
        if step == 0:
            c.state(linuxcnc.STATE_ESTOP_RESET)
            c.state(linuxcnc.STATE_ON)
            _hg["step"] = 1
        elif step == 1 and s.task_state == linuxcnc.STATE_ON:
            c.mode(linuxcnc.MODE_MANUAL)
            c.teleop_enable(0)
            c.home(-1)
            _hg["step"] = 2
        elif step == 2 and all(s.homed[j] for j in range(s.joints)):
            c.mode(linuxcnc.MODE_AUTO)
            c.wait_complete()
            c.program_open(os.path.abspath(inifile.find("DISPLAY", "OPEN_FILE")))
            c.auto(linuxcnc.AUTO_RUN, 0)
            _hg["step"] = 3
        if _hg["step"] < 3:
            root_window.after(200, _hg_autostart)

    root_window.after(2000, _hg_autostart)
