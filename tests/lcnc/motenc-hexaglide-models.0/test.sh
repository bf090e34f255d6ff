# Every parametrization (module parameter model=) with the drives off: one
# line "model first-count first-time last-count last-time" per model, from
# periods 500 and 1499 of encoder 4 while the machine sinks.
set -e
for m in standard reduced-joints reduced-cartesian fused-cartesian; do
    sed "s/@MODEL@/$m/" sink.hal.in > sink.hal
    halrun -f sink.hal > samples
    if grep -q '^overrun$' samples; then echo overrun; fi
    awk -v m=$m 'NR == 501 { c = $1; t = $2 } NR == 1500 { print m, c, t, $1, $2 }' samples
done
