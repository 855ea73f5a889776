#!/usr/bin/env bash
# Performance regression guard: instruction counts (callgrind), not wall-clock time.
#
#   perf/guard.sh                 # measure, compare with perf/baseline.json, exit 1 on regression
#   perf/guard.sh --update        # measure and rewrite perf/baseline.json
#   options: --probe PATH (default build/adrsph_perf_probe), --baseline FILE,
#            --tolerance T (default: the baseline's, 0.10), --steps N (default 10)
#
# The probe (perf/perf_probe.cpp) runs 10 steps of the coarse reactor (dx = 0.5 mm) for the
# modern, conventional and prescribed-flow variants on one OpenMP thread; callgrind counts
# only those steps, one dump per variant. Measured per variant:
#   <variant>.step        every instruction executed inside the 10 steps
#   <variant>.force_pass  inclusive count of the fused force pass (functions named
#                         interaction_pass<...> or interaction_pass_with<...>, the largest
#                         inclusive count among them)
# A count more than `tolerance` above the baseline fails the guard. Counts below the
# baseline pass (refresh the baseline after an optimisation so that the gain is kept).
# See perf/README.md for the method and why 10% is the tolerance.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
probe="$root/build/adrsph_perf_probe"
baseline="$root/perf/baseline.json"
update=0
tolerance=""
steps=10
while (($#)); do
  case "$1" in
    --update) update=1 ;;
    --probe) probe="$2"; shift ;;
    --baseline) baseline="$2"; shift ;;
    --tolerance) tolerance="$2"; shift ;;
    --steps) steps="$2"; shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "guard: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

command -v valgrind >/dev/null || { echo "guard: valgrind not found (tools/setup.sh installs it)" >&2; exit 2; }
command -v callgrind_annotate >/dev/null || { echo "guard: callgrind_annotate not found" >&2; exit 2; }
[[ -x "$probe" ]] || { echo "guard: probe $probe not built (cmake --build build --target adrsph_perf_probe)" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

start=$SECONDS
if ! OMP_NUM_THREADS=1 valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no \
      --callgrind-out-file="$work/cg.out" "$probe" "$steps" >"$work/probe.log" 2>"$work/valgrind.log"; then
  cat "$work/probe.log" "$work/valgrind.log" >&2
  echo "guard: the probe failed under valgrind" >&2
  exit 2
fi
for f in "$work"/cg.out.*; do
  callgrind_annotate --inclusive=yes --threshold=100 "$f" >"$f.annotate"
done

# What the counts depend on besides the source: compiler, build type, -march.
cache="$(dirname "$probe")/CMakeCache.txt"
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$cache" 2>/dev/null || true; }
compiler="$(cache_value CMAKE_CXX_COMPILER)"
compiler_version="$(${compiler:-c++} --version 2>/dev/null | head -1 || true)"
build="$(cache_value CMAKE_BUILD_TYPE), ADRSPH_ARCH=$(cache_value ADRSPH_ARCH)"

GUARD_WORK="$work" GUARD_BASELINE="$baseline" GUARD_UPDATE="$update" GUARD_TOLERANCE="$tolerance" \
GUARD_STEPS="$steps" GUARD_COMPILER="$compiler_version" GUARD_BUILD="$build" GUARD_VALGRIND="$(valgrind --version)" \
GUARD_SECONDS="$((SECONDS - start))" python3 - <<'EOF'
import glob, json, os, re, sys

work = os.environ["GUARD_WORK"]
baseline_path = os.environ["GUARD_BASELINE"]
steps = int(os.environ["GUARD_STEPS"])

# One dump per variant: its trigger names the variant, its totals line is the count of the
# collected region (the steps only); the annotation gives per-function inclusive counts.
counts = {}
for path in sorted(glob.glob(os.path.join(work, "cg.out.*[0-9]"))):
    name, total = None, None
    with open(path) as f:
        for line in f:
            m = re.match(r"desc: Trigger: Client Request: (\S+)", line)
            if m:
                name = m.group(1)
            # "totals" sums the costs in this dump; the "summary" line is unreliable when
            # instrumentation is switched on and off (callgrind 3.19), so it is not used.
            m = re.match(r"totals: (\d+)", line)
            if m:
                total = int(m.group(1))
    if name is None or total is None:
        sys.exit(f"guard: cannot read {path}")
    force = 0
    with open(path + ".annotate") as f:
        for line in f:
            m = re.match(r"\s*([\d,]+)\s+(?:\([^)]*\)\s+)?(.*)$", line)
            # interaction_pass<...> and the body it runs, interaction_pass_with<...>
            if m and re.search(r"interaction_pass(_with)?<", m.group(2)):
                force = max(force, int(m.group(1).replace(",", "")))
    if force == 0:
        sys.exit(f"guard: no function named interaction_pass<...> in the {name} profile "
                 "(renamed? update perf/guard.sh and the baseline)")
    counts[f"{name}.step"] = total
    counts[f"{name}.force_pass"] = force

if not counts:
    sys.exit("guard: no callgrind dumps: was the probe built without <valgrind/callgrind.h>?")

if os.environ["GUARD_UPDATE"] == "1":
    tol = float(os.environ["GUARD_TOLERANCE"] or 0.10)
    data = {
        "what": "callgrind instruction counts (Ir) of perf/perf_probe.cpp, see perf/README.md",
        "steps": steps,
        "tolerance": tol,
        "compiler": os.environ["GUARD_COMPILER"],
        "build": os.environ["GUARD_BUILD"],
        "valgrind": os.environ["GUARD_VALGRIND"],
        "counts": counts,
    }
    with open(baseline_path, "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    print(f"guard: wrote {baseline_path}")
    for k, v in counts.items():
        print(f"  {k:26s} {v:>16,d}")
    sys.exit(0)

with open(baseline_path) as f:
    base = json.load(f)
tol = float(os.environ["GUARD_TOLERANCE"] or base.get("tolerance", 0.10))
if base.get("steps") != steps:
    sys.exit(f"guard: baseline is for {base.get('steps')} steps, measured {steps}")
print(f"perf guard: callgrind Ir, {steps} steps per variant, dx = 0.5 mm, 1 thread, "
      f"tolerance +{100 * tol:.0f}%  ({os.environ['GUARD_SECONDS']} s)")
for key, env in (("compiler", "GUARD_COMPILER"), ("build", "GUARD_BUILD")):
    if base.get(key) and base[key] != os.environ[env]:
        print(f"  note: baseline {key} '{base[key]}', now '{os.environ[env]}': the counts "
              "are not comparable; refresh with --update if this is the new normal")
print(f"  {'metric':26s} {'baseline':>16s} {'now':>16s} {'ratio':>7s}")
failed = []
for k in sorted(set(base["counts"]) | set(counts)):
    b, n = base["counts"].get(k), counts.get(k)
    if b is None or n is None:
        print(f"  {k:26s} {b or '-':>16} {n or '-':>16}    missing")
        failed.append(k)
        continue
    ratio = n / b
    bad = ratio > 1.0 + tol
    print(f"  {k:26s} {b:>16,d} {n:>16,d} {ratio:7.3f}{'  REGRESSION' if bad else ''}")
    if bad:
        failed.append(k)
if failed:
    print(f"perf guard: FAILED ({', '.join(failed)}). If the extra work is intended, "
          "refresh the baseline: perf/guard.sh --update (see perf/README.md)")
    sys.exit(1)
print("perf guard: ok")
EOF
