// Checkpoint/restart of the solver (adrsph/checkpoint.hpp): the state a snapshot keeps and
// how restore() rebuilds the rest from it.
#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "integrator/sph_solver.hpp"

namespace adrsph {

SolverSnapshot SphSolver::snapshot() const {
  const std::size_t n = store_.size();
  SolverSnapshot s;
  // The state fields of the store's field list, by name, as views (checkpoint.hpp).
  ParticleStore::for_each_field(
      store_, [&](const auto& a, ParticleStore::Role role, const char* name) {
        if (role != ParticleStore::Role::state) return;
        using T = typename std::decay_t<decltype(a)>::value_type;
        s.particles.of<T>().emplace_back(name, std::span<const T>(a.data(), n));
      });
  s.inflow_row_tail = scene_.inflow_row_tails();
  s.t = t_;
  s.steps = steps_;
  s.lost = lost_;
  s.lost_reported = lost_reported_;
  s.rebuilds = rebuilds_;
  s.two_pass_builds = two_pass_builds_;
  s.particle_steps = particle_steps_;
  static_assert(sizeof(s.ledger) == sizeof(double) * 4 * Case::kMaxSpecies);
  for (int e = 0; e < Case::kMaxSpecies; ++e) {
    const SpeciesLedger& l = ledgers_[static_cast<std::size_t>(e)];
    std::copy_n(std::array{l.inflow, l.outflow, l.buffer_exchange, l.reaction}.begin(), 4,
                s.ledger.begin() + 4 * e);
  }
  s.entered = crossings_.entered;
  s.left = crossings_.left;
  s.phase_seconds = timers_.totals();
  return s;
}

void SphSolver::restore(const SolverSnapshot& s) {
  // Each state field of the store from the snapshot's array of its name and type.
  std::size_t n = 0;
  bool first = true;
  ParticleStore::for_each_field(store_, [&](auto& a, ParticleStore::Role role, const char* name) {
    if (role != ParticleStore::Role::state) return;
    using T = typename std::decay_t<decltype(a)>::value_type;
    const NamedArray<T>* named = nullptr;
    for (const NamedArray<T>& candidate : s.particles.of<T>())
      if (candidate.name == name) named = &candidate;
    if (!named)
      throw std::invalid_argument(std::string("checkpoint has no particle array ") + name);
    const std::span<const T> v = named->values();
    if (first) {
      n = v.size();
      first = false;
      store_.resize(n);
    }
    if (v.size() != n) throw std::invalid_argument("checkpoint particle arrays differ in length");
    std::copy(v.begin(), v.end(), a.begin());
  });
  scene_.set_inflow_row_tails(s.inflow_row_tail);
  for (std::size_t i = 0; i < n; ++i) {
    if (store_.kind[i] > kOutletByte)
      throw std::invalid_argument("checkpoint particle kind out of range");
    store_.set_kind(i, static_cast<Kind>(store_.kind[i]));  // the derived mask
    if (store_.needs().shifting) store_.sx[i] = store_.sy[i] = 0.0f;
  }
  // The particles were saved in cell order right after a rebuild: the stable sort keeps
  // them in place and the lists come out as they were.
  rebuild();
  // Snapshots are taken after a step, which leaves the next densities predicted (the
  // conventional scheme): the continued run takes them as the uninterrupted one does.
  density_predicted_ = store_.needs().predicted_density && predict_density_ && s.steps > 0;
  t_ = s.t;
  steps_ = s.steps;
  lost_ = s.lost;
  lost_reported_ = s.lost_reported;
  rebuilds_ = s.rebuilds;
  two_pass_builds_ = s.two_pass_builds;
  particle_steps_ = s.particle_steps;
  for (int e = 0; e < Case::kMaxSpecies; ++e) {
    const double* l = s.ledger.data() + 4 * e;
    ledgers_[static_cast<std::size_t>(e)] = {l[0], l[1], l[2], l[3]};
  }
  crossings_ = {s.entered, s.left};
  timers_.set_totals(s.phase_seconds);
}

}  // namespace adrsph
