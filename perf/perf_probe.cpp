// Fixed, small workload for the instruction-count regression guard (perf/guard.sh).
//
// For each variant (modern, conventional, prescribed) it builds the coarse reactor
// (dx = 0.5 mm, Case defaults otherwise), takes one warm-up step, then runs `steps` more
// steps (default 10) with callgrind collecting only inside that loop, and dumps the counts
// under the variant's name. Set-up, warm-up and exit are not counted, and callgrind does not
// even instrument them (--instr-atstart=no), which keeps the guard fast.
// One OpenMP thread: the count is then deterministic for a given binary.
//
// Outside valgrind the client requests are no-ops: the probe just runs the steps.
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "adrsph/case.hpp"
#include "integrator/sph_solver.hpp"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define ADRSPH_HAVE_CALLGRIND 1
#else
#define ADRSPH_HAVE_CALLGRIND 0
#endif

namespace {

using namespace adrsph;

void start_counting() {
#if ADRSPH_HAVE_CALLGRIND
  CALLGRIND_START_INSTRUMENTATION;
  CALLGRIND_TOGGLE_COLLECT;
#endif
}

void stop_counting(const char* name) {
#if ADRSPH_HAVE_CALLGRIND
  CALLGRIND_TOGGLE_COLLECT;
  CALLGRIND_DUMP_STATS_AT(name);
  CALLGRIND_STOP_INSTRUMENTATION;
#else
  (void)name;
#endif
}

bool run(const char* name, Scheme scheme, Flow flow, int steps) {
  Case c;
  c.name = std::string("perf_probe_") + name;
  c.particles.dx = 0.5;
  c.scheme = scheme;
  c.flow = flow;
  c.output.progress = false;
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen;
  bool ok = solver.step(dt);  // warm-up: lazy symbol binding, first-touch allocations
  start_counting();
  for (int k = 0; k < steps && ok; ++k) ok = solver.step(dt);
  stop_counting(name);
  std::printf("%-13s %zu particles, %d steps, dt %.3g s, t %.4g s%s\n", name,
              solver.particles().size(), steps, dt, solver.time(), ok ? "" : " FAILED");
  if (!ok) std::fprintf(stderr, "perf_probe: %s: %s\n", name, solver.failure().c_str());
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const int steps = argc > 1 ? std::atoi(argv[1]) : 10;
    omp_set_num_threads(1);
    bool ok = run("modern", Scheme::modern, Flow::wcsph, steps);
    ok = run("conventional", Scheme::conventional, Flow::wcsph, steps) && ok;
    ok = run("prescribed", Scheme::modern, Flow::prescribed, steps) && ok;
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "perf_probe: %s\n", e.what());
    return 1;
  }
}
