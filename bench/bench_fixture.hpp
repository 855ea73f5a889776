// Shared set-up for the benchmarks: the reactor case at a given resolution, a solver built
// from it, and the neighbour structures and constants a single pass needs.
//
// The fixture takes the solver's kernel, physics constants, grid and cut-off, and keeps a
// neighbour list of its own (the passes are timed on it; the solver's is private).
#pragma once

#include <omp.h>

#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "adrsph/case.hpp"
#include "boundaries/channel_scene.hpp"
#include "integrator/sph_solver.hpp"
#include "kernels/quintic_kernel.hpp"
#include "neighbours/cell_grid.hpp"
#include "neighbours/neighbour_list.hpp"
#include "schemes/pass_context.hpp"

namespace adrsph::bench {

// The three resolutions of the reactor (Case defaults: length 100 mm, half width 5 mm), as
// benchmark arguments in micrometres: dx = 0.5, 0.25, 0.125 mm.
inline constexpr long kResolutionsUm[] = {500, 250, 125};

enum class Variant { modern, conventional, prescribed };

inline Case reactor_case(Variant v, double dx) {
  Case c;
  c.name = "bench_reactor";
  c.particles.dx = dx;
  c.scheme = v == Variant::conventional ? Scheme::conventional : Scheme::modern;
  c.flow = v == Variant::prescribed ? Flow::prescribed : Flow::wcsph;
  c.output.progress = false;
  return c;
}

struct Fixture {
  Case c;
  SphSolver solver;
  QuinticKernel kernel;
  PhysicsConstants phys;
  CellGrid grid;
  NeighbourList list;
  double cutoff = 0.0;
  double dt = 0.0;

  Fixture(Variant v, double dx)
      : c(reactor_case(v, dx)),
        solver(c),
        kernel(solver.kernel()),
        phys(solver.physics()),
        grid(solver.grid()),
        cutoff(solver.cutoff()) {
    dt = solver.dt_limits().chosen;
    phys.set_step(c, dt);  // the shifting constants, as the solver sets them at every step
    // Derived fields (p, rho of the walls) as a real evaluation leaves them.
    solver.evaluate();
    std::vector<std::uint32_t> order, outside;
    sort(order, outside);
    for (std::size_t i = 0; i < order.size(); ++i)
      if (order[i] != i || !outside.empty())
        throw std::logic_error("bench fixture: grid differs from the solver's");
    build_list();
    if (std::abs(list.mean_neighbours() - solver.mean_neighbours()) > 1e-9)
      throw std::logic_error("bench fixture: neighbour list differs from the solver's");
  }

  std::size_t size() const { return solver.particles().size(); }
  PassContext context() const { return PassContext{kernel, list, phys}; }

  // The solver keeps its particles sorted with an identical grid, so this sort finds them in
  // order (no permutation needed for the passes).
  void sort(std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& outside) {
    const ParticleStore& s = solver.particles();
    grid.sort(std::span(s.x).first(size()), std::span(s.y).first(size()), order, outside);
  }
  void build_list() {
    const ParticleStore& s = solver.particles();
    list.build(grid, std::span(s.x).first(size()), std::span(s.y).first(size()), cutoff,
               static_cast<std::uint32_t>(size()), NeighbourList::Width::automatic,
               solver.wall_rows());  // the solver's rule
  }
};

// Steps a stepping fixture takes before it is timed: until the fastest particle has moved
// 8 h (8 (c0 + u_max) / (cfl u_max) steps, the same number at every resolution), so that
// the lists have been rebuilt many times and the particles have left the lattice, as in a
// run, instead of timing the first steps from a perfect lattice.
inline int disorder_steps(const Fixture& fx) {
  const Case& c = fx.c;
  return static_cast<int>(std::ceil(8.0 * c.h() / (c.u_max() * fx.dt)));
}

// Fixtures are built once per (variant, resolution, purpose) and kept for the whole run:
// the fine case takes about a second to construct. `purpose` separates fixtures whose
// state a benchmark advances (full steps: stepped into disorder first, disorder_steps)
// from the ones the passes only read.
inline Fixture& fixture(Variant v, long dx_um, int purpose = 0) {
  static std::map<std::tuple<Variant, long, int>, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[{v, dx_um, purpose}];
  if (!slot) {
    slot = std::make_unique<Fixture>(v, 1e-3 * static_cast<double>(dx_um));
    if (purpose != 0) {
      const int steps = disorder_steps(*slot);
      for (int k = 0; k < steps; ++k)
        if (!slot->solver.step(slot->dt))
          throw std::runtime_error("bench fixture: " + slot->solver.failure());
    }
  }
  return *slot;
}

// Sets the OpenMP thread count for one benchmark and restores it afterwards.
class ThreadScope {
 public:
  explicit ThreadScope(int threads) : saved_(omp_get_max_threads()) {
    if (threads > 0) omp_set_num_threads(threads);
  }
  ~ThreadScope() { omp_set_num_threads(saved_); }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
};

}  // namespace adrsph::bench
