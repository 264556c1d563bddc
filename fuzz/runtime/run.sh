#!/usr/bin/env bash
# Runtime fuzzing: builds each libFuzzer harness (clang, ASan + UBSan) against dictionaries
# generated into build/fuzz/runtime, runs it for RUNS executions from its seed corpus, then
# runs the persistence fault test. Writes fuzz/results/runtime.json and faults.json.
# A finding (crash, sanitizer report, timeout, property violation) is copied to
# fuzz/runtime/regressions/<harness>/ and makes the script exit non-zero.
#
#   bash fuzz/runtime/run.sh [RUNS]         (default 10000000; FUZZ_HARNESSES="sdo od" for a subset)
set -euo pipefail

RUNS=${1:-10000000}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
HERE=$ROOT/fuzz/runtime
OUT=$ROOT/build/fuzz/runtime
RESULTS=$ROOT/fuzz/results
HARNESSES=${FUZZ_HARNESSES:-sdo pdo od}
PY=$ROOT/.venv/bin/python
[ -x "$PY" ] || PY=python3
CC=${FUZZ_CC:-clang}
FLAGS=(-std=c99 -Wall -Wextra -Werror -pedantic -O1 -g -fno-omit-frame-pointer
       -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all)
RUNTIME=(odg.c odg_persist.c odg_persist_slot.c odg_persist_fixed.c odg_persist_migrate.c odg_node.c odg_sdo.c odg_pdo.c odg_err.c odg_sync.c odg_hb.c odg_lss.c odg_time.c)

declare -A DICT=([sdo]=alltypes [pdo]=pdo_node [od]=alltypes)

rm -rf "$OUT"
mkdir -p "$OUT/gen" "$RESULTS"
"$ROOT/.venv/bin/odgen" generate "$ROOT/tests/fixtures/generate/alltypes.eds" \
    --options "$ROOT/tests/fixtures/generate/alltypes.toml" -o "$OUT/gen/alltypes" >/dev/null
"$ROOT/.venv/bin/odgen" generate "$ROOT/tests/node/pdo-node.eds" -o "$OUT/gen/pdo_node" >/dev/null

rows=$OUT/rows.tsv
: >"$rows"
findings_total=0
for h in $HARNESSES; do  # every harness is built before any runs
    d=${DICT[$h]}
    "$CC" "${FLAGS[@]}" -I"$OUT/gen/$d" -I"$ROOT/runtime" -I"$HERE" "$HERE/fuzz_$h.c" "$OUT/gen/$d/$d.c" \
        "${RUNTIME[@]/#/$ROOT/runtime/}" -o "$OUT/fuzz_$h"
done
for h in $HARNESSES; do
    exe=$OUT/fuzz_$h
    mkdir -p "$OUT/corpus/$h" "$OUT/artifacts/$h"
    log=$OUT/fuzz_$h.log
    start=$(date +%s.%N)
    status=0
    nice -n 10 "$exe" -runs="$RUNS" -seed=1 -max_len=1024 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$OUT/artifacts/$h/" \
        "$OUT/corpus/$h" "$HERE/seeds/$h" >"$log" 2>&1 || status=$?
    end=$(date +%s.%N)
    found=$(find "$OUT/artifacts/$h" -type f | wc -l)
    if [ "$status" -ne 0 ] && [ "$found" -eq 0 ]; then
        found=1  # the harness failed without leaving an input (e.g. a startup fault)
    fi
    if [ "$found" -gt 0 ]; then
        mkdir -p "$HERE/regressions/$h"
        find "$OUT/artifacts/$h" -type f -exec cp {} "$HERE/regressions/$h/" \;
        echo "fuzz_$h: $found finding(s), inputs copied to fuzz/runtime/regressions/$h/; log: $log" >&2
        tail -n 40 "$log" >&2
    fi
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1 | sed 's/cov: //')
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$h" "${execs:-0}" "$start" "$end" "${cov:-0}" "$found" >>"$rows"
    findings_total=$((findings_total + found))
    echo "fuzz_$h: ${execs:-0} executions, cov ${cov:-0}, $found finding(s)"
done

"$PY" - "$rows" "$RESULTS/runtime.json" "$RUNS" "$CC" <<'PYEOF'
import json, sys
rows_path, out, budget, cc = sys.argv[1:]
rows = []
for line in open(rows_path, encoding="utf-8"):
    h, execs, start, end, cov, found = line.rstrip("\n").split("\t")
    secs = float(end) - float(start)
    rows.append([h, int(execs), round(secs, 1), int(int(execs) / secs) if secs > 0 else 0, int(cov), int(found)])
data = {
    "title": "Runtime fuzzing (libFuzzer, AddressSanitizer, UndefinedBehaviorSanitizer)",
    "columns": ["harness", "executions", "seconds", "exec/s", "coverage (cov)", "findings"],
    "rows": rows,
    "notes": [
        f"budget: {int(budget):,} executions per harness, one harness at a time, seed 1, inputs up to 1024 bytes, from fuzz/runtime/seeds/",
        f"compiler: {cc} -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all",
        "sdo: the SDO server fed frame sequences (expedited, segmented, block, aborts, short frames, "
        "any COB-ID, NMT, time, a busy controller) on the alltypes dictionary",
        "pdo: PDO mappings set through SDO from the input, then RPDO frames, SYNCs, time and "
        "application requests on tests/node/pdo-node.eds",
        "od: odg_read/odg_write/odg_write_part/odg_check_mapping/odg_hook_register on every data type "
        "of alltypes; odg_verify must hold at the end",
        "cov: edges covered at the end of the run (libFuzzer's cov:), over the harness and the runtime",
    ],
}
with open(out, "w", encoding="utf-8") as f:
    json.dump(data, f, indent=2)
    f.write("\n")
PYEOF

# The persistence fault test writes its own figures.
if [ -f "$ROOT/tests/runtime/test_faults.c" ]; then
    gcc -std=c99 -Wall -Wextra -Werror -pedantic -O2 -I"$ROOT/runtime" -I"$ROOT/tests/runtime" \
        "$ROOT/tests/runtime/test_faults.c" "$ROOT/tests/runtime/nv_fault.c" "$ROOT/tests/runtime/td.c" \
        "$ROOT/runtime/odg.c" "$ROOT"/runtime/odg_persist*.c -o "$OUT/test_faults"
    "$OUT/test_faults" --json "$RESULTS/faults.json" | tail -n 1
fi

if [ "$findings_total" -gt 0 ]; then
    echo "runtime fuzzing: $findings_total finding(s)" >&2
    exit 1
fi
