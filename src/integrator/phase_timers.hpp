// Wall-clock time per phase of a step, summed over the run (omp_get_wtime).
#pragma once

#include <omp.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace adrsph {

enum class Phase {
  sort,
  neighbours,
  density,
  boundaries,
  forces,
  species,
  integration,
  probes,
  output,
  count
};

class PhaseTimers {
 public:
  void add(Phase p, double seconds) { total_[static_cast<int>(p)] += seconds; }
  // All totals in Phase order, and back (checkpoint/restart).
  std::vector<double> totals() const { return {total_.begin(), total_.end()}; }
  void set_totals(const std::vector<double>& t) {
    for (std::size_t i = 0; i < total_.size() && i < t.size(); ++i) total_[i] = t[i];
  }
  std::vector<std::pair<std::string, double>> table() const {
    static const char* names[] = {"sort",    "neighbours",  "density", "boundaries", "forces",
                                  "species", "integration", "probes",  "output"};
    std::vector<std::pair<std::string, double>> t;
    for (int i = 0; i < static_cast<int>(Phase::count); ++i) t.emplace_back(names[i], total_[i]);
    return t;
  }

 private:
  std::array<double, static_cast<int>(Phase::count)> total_{};
};

class ScopedPhase {
 public:
  ScopedPhase(PhaseTimers& t, Phase p) : timers_(t), phase_(p), start_(omp_get_wtime()) {}
  ~ScopedPhase() { timers_.add(phase_, omp_get_wtime() - start_); }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseTimers& timers_;
  Phase phase_;
  double start_;
};

}  // namespace adrsph
