#!/usr/bin/env bash
# Where a run's time goes and how it scales from 1 to 2 threads, from the engine's own phase
# timers (run.json `phase_seconds`): the same run, N steps from a cold start, once per thread
# count, then one table of seconds per phase, the 1 -> 2 thread ratio and each phase's share.
#
#   perf/phases.sh [--dx 0.125] [--steps 1000] [--scheme modern|conventional|prescribed]
#                  [--threads "1 2"] [--exe build/adrsph]
#
# CMake target: `cmake --build build --target bench_phases` (the fine modern case). Quote the
# load average the table prints with it: the machine is shared (perf/README.md, section 3).
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
exe="$root/build/adrsph"
dx=0.125
steps=1000
scheme=modern
threads="1 2"
while (($#)); do
  case "$1" in
    --dx) dx="$2"; shift ;;
    --steps) steps="$2"; shift ;;
    --scheme) scheme="$2"; shift ;;
    --threads) threads="$2"; shift ;;
    --exe) exe="$2"; shift ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) echo "phases: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[[ -x "$exe" ]] || { echo "phases: $exe not found: build first (tools/setup.sh)" >&2; exit 2; }
case "$scheme" in
  modern|conventional) sets=(--set "scheme=$scheme") ;;
  prescribed) sets=(--set flow=prescribed) ;;
  *) echo "phases: --scheme must be modern, conventional or prescribed" >&2; exit 2 ;;
esac

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for t in $threads; do
  "$exe" run "$root/cases/lfr.toml" "${sets[@]}" --set "particles.dx=$dx" \
    --set "time.max_steps=$steps" --set time.warm_start=false --set output.progress=false \
    --threads "$t" --out "$work/t$t" >/dev/null
done
python3 - "$work" "$scheme" "$dx" "$steps" $threads <<'PY'
import json, os, sys
work, scheme, dx, steps, threads = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
runs = {t: json.load(open(os.path.join(work, "t" + t, "run.json"))) for t in threads}
first, last = runs[threads[0]], runs[threads[-1]]
print("%s, dx = %s mm, %s steps from a cold start, %d particles; load average %s"
      % (scheme, dx, steps, first["particles"], os.getloadavg()[0]))
head = "%-12s" % "phase" + "".join("%12s" % ("%s thr [s]" % t) for t in threads)
if len(threads) > 1:
    head += "%10s" % "ratio"
head += "%10s" % "share"
print(head)
for phase in first["phase_seconds"]:
    secs = [runs[t]["phase_seconds"][phase] for t in threads]
    line = "%-12s" % phase + "".join("%12.3f" % s for s in secs)
    if len(threads) > 1:
        line += "%10s" % ("%.2f" % (secs[0] / secs[-1]) if secs[-1] > 0 else "-")
    line += "%9.1f%%" % (100.0 * secs[-1] / max(last["wall_seconds"], 1e-12))
    print(line)
walls = [runs[t]["wall_seconds"] for t in threads]
line = "%-12s" % "wall" + "".join("%12.3f" % w for w in walls)
if len(threads) > 1:
    line += "%10.2f" % (walls[0] / walls[-1])
print(line)
print("particle-steps/s: " + ", ".join("%s thread(s) %.3g" % (t, runs[t]["particle_steps_per_second"])
                                       for t in threads))
PY
