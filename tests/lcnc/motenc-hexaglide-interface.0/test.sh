#!/bin/bash
# The board's interface under motenc.0.: one line "kind type dir name" per
# pin and parameter, and "funct name" per function, sorted. HAL's own
# FUNCT.time / .tmax / .tmax-increased parameters are left out.
set -e
halrun -f list.hal > raw
awk '
/^Component Pins/ { kind = "pin"; next }
/^Parameters/ { kind = "param"; next }
/^Exported Functions/ { kind = "funct"; next }
$1 ~ /^[0-9]+$/ && kind == "funct" && NF >= 6 { print "funct", $6; next }
$1 ~ /^[0-9]+$/ && NF >= 5 && $5 !~ /\.(time|tmax|tmax-increased)$/ { print kind, $2, $3, $5 }
' raw | LC_ALL=C sort
