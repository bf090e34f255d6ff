#!/bin/sh
# install-deps.sh - install the Debian 12 packages this project needs, once.
# Usage: tools/install-deps.sh [build|test|demo|bench|run|tune|fmu]
# Installs only what is missing; uses sudo when not root.
set -e
need="linuxcnc-uspace linuxcnc-uspace-dev build-essential man-db"
# fmusim (make fmu): libxml2, minizip/zlib, SUNDIALS' CVODE; zip packs the FMU, xxd and
# python3-lxml turn the FMI schema into fmusim's header; tcc, a C compiler without GCC's
# extensions, builds the FMU's sources/ as MSVC would (tests/fmu/test_fmu_sources)
fmu="libxml2-dev zlib1g-dev libminizip-dev libsundials-dev pkg-config zip xxd python3-lxml tcc"
case "$1" in
  test)  need="$need $fmu libmujoco-dev python3-sympy python3-numpy python3-matplotlib python3-scipy cppcheck clang clang-tidy libclang-rt-14-dev bc xvfb imagemagick" ;;
  demo)  need="$need python3-matplotlib python3-numpy xvfb" ;;
  bench) need="$need libmujoco-dev valgrind" ;;
  run)   need="$need xvfb" ;;
  tune)  need="$need python3-numpy python3-scipy python3-matplotlib" ;;
  fmu)   need="$need $fmu python3-numpy python3-matplotlib" ;;
esac
missing=""
for p in $need; do
  dpkg-query -W -f='${Status}\n' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "install-deps: installing$missing" >&2
SUDO=""
[ "$(id -u)" = 0 ] || SUDO=sudo
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing >/dev/null
