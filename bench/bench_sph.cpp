// Google Benchmark suite for the hot pieces of the engine at the three reactor resolutions
// (argument dx_um: 500, 250, 125 = dx 0.5, 0.25, 0.125 mm). See perf/README.md for how to
// run it and how to read the counters:
//   particle-evals/s  particles (all kinds, as in SphSolver::particle_steps) times passes
//   particle-steps/s  particles times full midpoint steps (two evaluations each)
// OpenMP code is timed in real (wall) time. The passes use the OMP_NUM_THREADS threads; the
// full steps take the thread count as their second argument (omp), so that 1 and 2 threads
// are compared in the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "bench_fixture.hpp"
#include "boundaries/boundary_extrapolation.hpp"
#include "schemes/density_passes.hpp"
#include "schemes/interaction_pass.hpp"
#include "schemes/scheme_traits.hpp"

namespace {

using namespace adrsph;
using adrsph::bench::fixture;
using adrsph::bench::Fixture;
using adrsph::bench::ThreadScope;
using adrsph::bench::Variant;

// Fixture purposes: passes read a fixture; full steps advance their own.
constexpr int kPasses = 0;
constexpr int kSteps = 1;

void per_particle(benchmark::State& state, std::size_t particles, const char* name) {
  state.counters[name] =
      benchmark::Counter(static_cast<double>(particles) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["particles"] = static_cast<double>(particles);
}

void resolutions(benchmark::internal::Benchmark* b) {
  b->ArgName("dx_um");
  for (long dx_um : adrsph::bench::kResolutionsUm) b->Arg(dx_um);
}

void resolutions_threads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dx_um", "omp"});
  for (long dx_um : adrsph::bench::kResolutionsUm)
    for (long threads : {1, 2}) b->Args({dx_um, threads});
}

// Kernel value and gradient factor over distances spread across the support (and a little
// beyond, as cached lists with a skin contain). Serial; counts kernel evaluations.
void BM_Kernel(benchmark::State& state) {
  const double h = 1e-3 * static_cast<double>(state.range(0));
  const QuinticKernel kernel(h);
  constexpr std::size_t kCount = 4096;
  std::vector<double> r(kCount);
  for (std::size_t k = 0; k < kCount; ++k)
    r[k] = 1.1 * kernel.support * static_cast<double>(k) / static_cast<double>(kCount);
  for (auto _ : state) {
    double w = 0.0, f = 0.0;
#pragma omp simd reduction(+ : w, f)
    for (std::size_t k = 0; k < kCount; ++k) {
      w += kernel.value(r[k]);
      f += kernel.gradient_factor(r[k]);
    }
    benchmark::DoNotOptimize(w);
    benchmark::DoNotOptimize(f);
  }
  state.counters["kernel-evals/s"] =
      benchmark::Counter(static_cast<double>(kCount) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Kernel)->Apply(resolutions);

// Morton counting sort of the cells and the permutation of every particle array, on a copy
// of the state (already nearly in order, as at a re-sort during a run).
void BM_MortonSort(benchmark::State& state) {
  Fixture& fx = fixture(Variant::modern, state.range(0), kPasses);
  ParticleStore store = fx.solver.particles();
  const std::size_t n = store.size();
  CellGrid grid = fx.grid;
  std::vector<std::uint32_t> order, outside;
  for (auto _ : state) {
    grid.sort(std::span(store.x).first(n), std::span(store.y).first(n), order, outside);
    store.permute(order);
    benchmark::ClobberMemory();
  }
  per_particle(state, n, "particle-evals/s");
}
BENCHMARK(BM_MortonSort)->Apply(resolutions)->Unit(benchmark::kMillisecond)->UseRealTime();

// Cached neighbour list (CSR, padded) from the sorted cell grid.
void BM_NeighbourList(benchmark::State& state) {
  Fixture& fx = fixture(Variant::modern, state.range(0), kPasses);
  for (auto _ : state) {
    fx.build_list();
    benchmark::ClobberMemory();
  }
  per_particle(state, fx.size(), "particle-evals/s");
  state.counters["neighbours"] = fx.list.mean_neighbours();
}
BENCHMARK(BM_NeighbourList)->Apply(resolutions)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same build on the particles of a run: the fixture is stepped into disorder first
// (disorder_steps), and the positions are sorted into the grid's order on a copy. On the
// lattice the in/out test of each candidate follows a pattern the branch predictor learns;
// in a run it does not, and that is the build the run pays for.
void BM_NeighbourListDisordered(benchmark::State& state) {
  Fixture& fx = fixture(Variant::modern, state.range(0), kSteps);
  const ParticleStore& s = fx.solver.particles();
  std::vector<std::uint32_t> order, outside;
  fx.grid.sort(std::span(s.x).first(fx.size()), std::span(s.y).first(fx.size()), order, outside);
  std::vector<double> x(order.size()), y(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) x[k] = s.x[order[k]], y[k] = s.y[order[k]];
  NeighbourList list;
  for (auto _ : state) {
    list.build(fx.grid, x, y, fx.cutoff, static_cast<std::uint32_t>(x.size()));
    benchmark::ClobberMemory();
  }
  per_particle(state, x.size(), "particle-evals/s");
  state.counters["neighbours"] = list.mean_neighbours();
  state.counters["one_pass"] = list.one_pass() ? 1 : 0;  // every build after the first, as in a run
}
BENCHMARK(BM_NeighbourListDisordered)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// rho_i = m sum_j W_ij (conventional scheme).
void BM_SummationDensity(benchmark::State& state) {
  Fixture& fx = fixture(Variant::conventional, state.range(0), kPasses);
  const PassContext ctx = fx.context();
  for (auto _ : state) {
    summation_density(fx.solver.particles(), ctx);
    benchmark::ClobberMemory();
  }
  per_particle(state, fx.size(), "particle-evals/s");
}
BENCHMARK(BM_SummationDensity)->Apply(resolutions)->Unit(benchmark::kMillisecond)->UseRealTime();

// Pressure and velocity of walls and buffers from the fluid (both WCSPH schemes).
void BM_BoundaryExtrapolation(benchmark::State& state) {
  Fixture& fx = fixture(Variant::conventional, state.range(0), kPasses);
  const PassContext ctx = fx.context();
  for (auto _ : state) {
    extrapolate_to_boundaries(fx.solver.particles(), ctx);
    benchmark::ClobberMemory();
  }
  per_particle(state, fx.size(), "particle-evals/s");
}
BENCHMARK(BM_BoundaryExtrapolation)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

template <class S>
constexpr Variant variant_of() {
  if constexpr (S::momentum && S::continuity) return Variant::modern;
  if constexpr (S::momentum && !S::continuity) return Variant::conventional;
  return Variant::prescribed;
}

// The fused force pass alone (momentum, continuity, shifting, species as the scheme needs),
// the fill of its neighbour records included (pair_records.hpp), as a step runs it.
template <class S>
void BM_ForcePass(benchmark::State& state) {
  Fixture& fx = fixture(variant_of<S>(), state.range(0), kPasses);
  const PassContext ctx = fx.context();
  PairRecords records;
  for (auto _ : state) {
    interaction_pass<S, false>(fx.solver.particles(), ctx, records);
    benchmark::ClobberMemory();
  }
  per_particle(state, fx.size(), "particle-evals/s");
}
BENCHMARK_TEMPLATE(BM_ForcePass, ModernScheme)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_ForcePass, ConventionalScheme)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_ForcePass, PrescribedFlow)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One whole evaluation as the solver does it (density, boundaries, volumes, force pass).
template <class S>
void BM_Evaluate(benchmark::State& state) {
  Fixture& fx = fixture(variant_of<S>(), state.range(0), kPasses);
  for (auto _ : state) {
    fx.solver.evaluate();
    benchmark::ClobberMemory();
  }
  per_particle(state, fx.size(), "particle-evals/s");
}
BENCHMARK_TEMPLATE(BM_Evaluate, ModernScheme)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_Evaluate, ConventionalScheme)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_Evaluate, PrescribedFlow)
    ->Apply(resolutions)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A full explicit midpoint step at the solver's stable dt, including the re-sorts and list
// rebuilds when they fall due (so their cost is amortised as in a run). The state advances
// from one iteration to the next, starting from the initial condition.
template <class S>
void BM_Step(benchmark::State& state) {
  const ThreadScope threads(static_cast<int>(state.range(1)));
  Fixture& fx = fixture(variant_of<S>(), state.range(0), kSteps);
  std::size_t particles = 0;
  for (auto _ : state) {
    particles += fx.size();
    if (!fx.solver.step(fx.dt)) {
      state.SkipWithError(fx.solver.failure().c_str());
      break;
    }
  }
  state.counters["particle-steps/s"] =
      benchmark::Counter(static_cast<double>(particles), benchmark::Counter::kIsRate);
  state.counters["particles"] = static_cast<double>(fx.size());
  state.counters["neighbours"] = fx.solver.mean_neighbours();
}
BENCHMARK_TEMPLATE(BM_Step, ModernScheme)
    ->Apply(resolutions_threads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_Step, ConventionalScheme)
    ->Apply(resolutions_threads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_TEMPLATE(BM_Step, PrescribedFlow)
    ->Apply(resolutions_threads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
