# hg_record.tcl - HALFILE of configs/hexaglide.ini: when a record file is
# asked for, record every servo period of the virtual board from the first
# one (tools/hg_record.py, docs/replay.md); otherwise do nothing.
# Asked for by the environment variable HG_RECORD=FILE or by
# [HEXAGLIDE]RECORD = FILE in the INI (a relative FILE is relative to the
# config directory). Runs after hexaglide.hal (the board's pins exist) and
# before LinuxCNC starts the threads.
set out ""
if {[info exists ::env(HG_RECORD)] && $::env(HG_RECORD) ne ""} {
    set out $::env(HG_RECORD)
} elseif {[info exists ::HEXAGLIDE(RECORD)]} {
    set out [lindex $::HEXAGLIDE(RECORD) 0]
}
if {$out ne ""} {
    loadusr -Wn hg_record [file join [file dirname [info script]] hg_record.py] [file normalize $out]
}
