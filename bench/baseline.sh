#!/bin/sh
# baseline.sh DIR CC [CFLAGS...] - the core of commit d20d9e5 (the step
# before issue 23's speed work) for bench_baseline: its src/ from git into
# DIR/src, compiled with the given compiler and flags (the same as today's),
# with bench/engine_shim.c, into one object DIR/engine_old.o whose only
# global symbols are old_engine_new, _step, _hold_volts, _free (every
# other symbol local, so it links beside today's core).
# Exit 0 when built (or up to date); 3 with a message when the repository
# has no commit d20d9e5 (a shallow clone or an exported tree).
BASELINE=d20d9e5
dir=$1; cc=$2; shift 2
cd "$(dirname "$0")/.." || exit 1
if ! git cat-file -e "$BASELINE^{commit}" 2>/dev/null; then
    echo "baseline.sh: this repository has no commit $BASELINE (shallow clone?): no baseline to compare with"
    exit 3
fi
out=$dir/engine_old.o
flags="$cc $*"                  # (built again when the compiler or the flags change: HOST_ARCH)
[ -f "$out" ] && [ "$out" -nt bench/engine_shim.c ] && [ "$out" -nt bench/baseline.sh ] &&
    [ "$(cat "$dir/flags" 2>/dev/null)" = "$flags" ] && exit 0
rm -rf "$dir/src" "$dir/obj" && mkdir -p "$dir/obj" || exit 1
git archive "$BASELINE" src | tar -x -C "$dir" || exit 1
objs=""
for f in "$dir"/src/hg_*.c "$dir"/src/generated/*.c bench/engine_shim.c; do
    o=$dir/obj/$(basename "$f" .c).o
    "$cc" "$@" -I"$dir/src" -I"$dir/src/generated" -DENGINE\(x\)=old_engine_\#\#x -c -o "$o" "$f" || exit 1
    objs="$objs $o"
done
# shellcheck disable=SC2086
ld -r -o "$dir/engine_all.o" $objs &&
objcopy -G old_engine_new -G old_engine_step -G old_engine_hold_volts -G old_engine_free \
    "$dir/engine_all.o" "$out" &&
echo "$flags" >"$dir/flags"
