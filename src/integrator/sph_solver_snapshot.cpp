// Checkpoint/restart of the solver (adrsph/checkpoint.hpp): the state a snapshot keeps and
// how restore() rebuilds the rest from it.
#include <stdexcept>
#include <string>

#include "integrator/sph_solver.hpp"

namespace adrsph {

SolverSnapshot SphSolver::snapshot() const {
  const std::size_t n = store_.size();
  SolverSnapshot s;
  auto copy = [n](const auto& a) { return std::vector(a.begin(), a.begin() + n); };
  s.x = copy(store_.x);
  s.y = copy(store_.y);
  s.vx = copy(store_.vx);
  s.vy = copy(store_.vy);
  s.rho = copy(store_.rho);
  s.c = copy(store_.c);
  s.p = copy(store_.p);
  s.vol = copy(store_.vol);
  s.kind = copy(store_.kind);
  s.inflow_row_tail = scene_.inflow_row_tails();
  s.t = t_;
  s.steps = steps_;
  s.lost = lost_;
  s.lost_reported = lost_reported_;
  s.rebuilds = rebuilds_;
  s.particle_steps = particle_steps_;
  s.ledger = {ledger_.inflow, ledger_.outflow, ledger_.buffer_exchange, ledger_.reaction};
  s.entered = crossings_.entered;
  s.left = crossings_.left;
  s.phase_seconds = timers_.totals();
  return s;
}

void SphSolver::restore(const SolverSnapshot& s) {
  const std::size_t n = s.x.size();
  for (std::size_t len : {s.y.size(), s.vx.size(), s.vy.size(), s.rho.size(), s.c.size(),
                          s.p.size(), s.vol.size(), s.kind.size()})
    if (len != n) throw std::invalid_argument("checkpoint particle arrays differ in length");
  scene_.set_inflow_row_tails(s.inflow_row_tail);
  store_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] > kOutletByte)
      throw std::invalid_argument("checkpoint particle kind out of range");
    store_.x[i] = s.x[i];
    store_.y[i] = s.y[i];
    store_.vx[i] = s.vx[i];
    store_.vy[i] = s.vy[i];
    store_.rho[i] = s.rho[i];
    store_.c[i] = s.c[i];
    store_.p[i] = s.p[i];
    store_.vol[i] = s.vol[i];
    store_.set_kind(i, static_cast<Kind>(s.kind[i]));
    if (store_.needs().shifting) store_.sx[i] = store_.sy[i] = 0.0f;
  }
  // The particles were saved in cell order right after a rebuild: the stable sort keeps
  // them in place and the lists come out as they were.
  rebuild();
  t_ = s.t;
  steps_ = s.steps;
  lost_ = s.lost;
  lost_reported_ = s.lost_reported;
  rebuilds_ = s.rebuilds;
  particle_steps_ = s.particle_steps;
  ledger_ = {s.ledger[0], s.ledger[1], s.ledger[2], s.ledger[3]};
  crossings_ = {s.entered, s.left};
  timers_.set_totals(s.phase_seconds);
}

}  // namespace adrsph
