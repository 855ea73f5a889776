// The guards of SphSolver::step: after every step, the state is checked (non-finite values,
// speed, density, concentration band; docs/robustness.md), and a failed step is undone and
// described (what, when, where). Particles lost at a re-sort are reported here too.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "integrator/midpoint.hpp"
#include "integrator/sph_solver.hpp"
#include "species/inlet_feed.hpp"

namespace adrsph {

namespace {
// |transport velocity|^2 of particle i: how far it moves (u + du for a shifting scheme's
// fluid particles, u otherwise; sx, sy exist only for a shifting scheme).
inline double transport_speed2(const ParticleStore& s, std::size_t i, bool shifting) {
  const bool shifts = shifting && s.kind[i] == kFluidByte;
  const double tx = s.vx[i] + (shifts ? s.sx[i] : 0.0), ty = s.vy[i] + (shifts ? s.sy[i] : 0.0);
  return tx * tx + ty * ty;
}
// Every value the guards read of particle i is finite (t2: its transport_speed2).
inline bool finite_state(const ParticleStore& s, std::size_t i, double t2) {
  return std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && std::isfinite(t2) &&
         std::isfinite(s.rho[i]) && std::isfinite(s.c[i]);
}
// Every rate of this step of fluid particle i is finite (advance() took the others as zero).
bool finite_rates(const ParticleStore& s, std::size_t i) {
  using midpoint::finite_rate;
  bool ok = true;
  ParticleStore::for_each_first_stage_pair(s, [&](const auto& rate, const auto& first) {
    ok = ok && finite_rate(rate[i]) && finite_rate(first[i]);
  });
  if (s.needs().species_start) {  // dc has no first-stage array then
    ok = ok && finite_rate(s.dc[i]);
    for (int e = 0; e < s.needs().more_species; ++e) ok = ok && finite_rate(s.dc_more[e][i]);
  }
  return ok;
}
}  // namespace

// Back from q1 = q0 + dt f(q_h) to q0 (midpoint.hpp), with the rates advance() used.
void SphSolver::undo_step(double dt) {
  using midpoint::rate_or_zero;
  ParticleStore& s = store_;
  const ParticleStore::Needs& needs = s.needs();
  const double h = 0.5 * dt;
  const std::size_t n = s.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t k = s.kind[i];
    if (k == kWallByte) continue;
    const bool fluid = k == kFluidByte;
    double tx = s.vx[i], ty = s.vy[i];  // the second stage's transport velocity
    if (fluid && needs.momentum) {
      s.vx[i] -= dt * rate_or_zero(s.ax[i]);  // u0
      s.vy[i] -= dt * rate_or_zero(s.ay[i]);
      tx = s.vx[i] + h * rate_or_zero(s.ax_first[i]);  // u_h
      ty = s.vy[i] + h * rate_or_zero(s.ay_first[i]);
      if (needs.shifting) {
        tx += rate_or_zero(s.sx[i]);
        ty += rate_or_zero(s.sy[i]);
      }
    }
    s.x[i] -= dt * tx;
    s.y[i] -= dt * ty;
    if (!fluid) continue;
    if (needs.continuity) s.rho[i] -= dt * rate_or_zero(s.drho[i]);
    if (needs.species_start) {
      s.c[i] = s.c_start[i];
      for (int e = 0; e < needs.more_species; ++e) s.c_more[e][i] = s.c_more_start[e][i];
    } else {
      s.c[i] -= dt * rate_or_zero(s.dc[i]);
      for (int e = 0; e < needs.more_species; ++e)
        s.c_more[e][i] -= dt * rate_or_zero(s.dc_more[e][i]);
    }
  }
}

// Particles a re-sort found outside the channel. The step that moved them is kept (they are
// removed already): the failure says so and stops the run there.
bool SphSolver::report_lost() {
  if (lost_ <= lost_reported_) return true;
  std::ostringstream m;
  m << (lost_ - lost_reported_) << " fluid particle(s) left the channel through a wall or "
    << "the inlet by t = " << t_ << " s (step " << steps_ << ").";
  failure_ = m.str();
  failure_site_ = {};
  failure_site_.kind = FailureKind::lost_particles;
  failure_site_.t = t_;
  failure_site_.step = steps_;
  failure_site_.value = static_cast<double>(lost_ - lost_reported_);
  lost_reported_ = lost_;
  return false;
}

bool SphSolver::check_state(double dt) {
  ScopedPhase timer(timers_, Phase::integration);
  ParticleStore& s = store_;
  const std::size_t n = s.size();
  int bad = 0;
  double vmax2 = 0.0, tmax2 = 0.0, drho_max = 0.0, c_dev = 0.0;
  // Diffusion and reaction keep C within [0, c_max] (maximum principle); the dilatation term
  // may move it slightly. A species step beyond its stability limit leaves this band fast.
  // A network's species share one band: none can exceed the moles all of them bring in.
  double c_max = 0.0;
  for (int sp = 0; sp < case_.species_count(); ++sp)
    c_max += std::max(feed_max(case_.species_at(sp)), case_.species_at(sp).c_init);
  const int more = s.needs().more_species;
  // The largest distance of particle i's C (any species) outside [0, c_max]; NaN if not finite.
  auto c_outside = [&](std::size_t i) {
    double d = std::max(s.c[i] - c_max, -s.c[i]);
    for (int e = 0; e < more; ++e) d = std::max({d, s.c_more[e][i] - c_max, -s.c_more[e][i]});
    for (int e = 0; e < more; ++e)
      if (!std::isfinite(s.c_more[e][i])) return std::nan("");
    return d;
  };
  const double rho0 = case_.fluid.rho0;
  const bool shifting = s.needs().shifting;  // sx, sy exist only for a shifting scheme
#pragma omp parallel for schedule(static) reduction(max : vmax2, tmax2, drho_max, c_dev) reduction(+ : bad)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] == kWallByte) continue;
    const double v2 = s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i];  // fluid velocity (Mach check)
    const double t2 = transport_speed2(s, i, shifting);
    const double c_off = more > 0 ? c_outside(i) : std::max(s.c[i] - c_max, -s.c[i]);
    const bool finite = finite_state(s, i, t2) && std::isfinite(c_off);
    bad += finite ? 0 : 1;
    vmax2 = std::max(vmax2, finite ? v2 : 0.0);
    tmax2 = std::max(tmax2, finite ? t2 : 0.0);
    drho_max = std::max(drho_max, finite ? std::fabs(s.rho[i] / rho0 - 1.0) : 0.0);
    if (finite) c_dev = std::max(c_dev, c_off);
  }
  bad += static_cast<int>(bad_rates_);  // fluid particles with a non-finite rate (advance())
  const double vmax = std::sqrt(vmax2);
  FailureKind kind = FailureKind::none;
  if (bad > 0)
    kind = FailureKind::non_finite;
  else if (case_.flow == Flow::wcsph && vmax > 0.5 * case_.c0())
    kind = FailureKind::speed;
  else if (case_.flow == Flow::wcsph && drho_max > 0.2)
    kind = FailureKind::density;
  else if (c_dev > 0.5 * c_max)
    kind = FailureKind::concentration;
  if (kind == FailureKind::none) {
    const double tmax = std::sqrt(tmax2);
    moved_abs_ += tmax * dt;
    return true;
  }
  // A guard tripped (rare): find the particle that failed worst, serially.
  std::size_t worst = 0;
  double worst_value = -1.0;
  int non_finite = 0;  // particles with a non-finite state or rate, each counted once
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] == kWallByte) continue;
    const double v2 = s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i];
    double value = 0.0;
    switch (kind) {
      case FailureKind::non_finite:
        value = finite_state(s, i, transport_speed2(s, i, shifting)) &&
                        std::isfinite(c_outside(i)) &&
                        (s.kind[i] != kFluidByte || finite_rates(s, i))
                    ? 0.0
                    : 1.0;
        non_finite += value > 0.0 ? 1 : 0;
        break;
      case FailureKind::speed:
        value = std::sqrt(v2);
        break;
      case FailureKind::density:
        value = std::fabs(s.rho[i] / rho0 - 1.0);
        break;
      default:
        value = c_outside(i);
        break;
    }
    if (value > worst_value) {
      worst_value = value;
      worst = i;
    }
  }
  const char* kind_of_worst = s.kind[worst] == kFluidByte   ? "fluid"
                              : s.kind[worst] == kInletByte ? "inlet"
                                                            : "outlet";
  // Restore the last good state (start of this step; walls were not advanced).
  undo_step(dt);
  density_predicted_ = false;
  failure_site_ = {kind, t_ + dt, steps_ + 1, s.x[worst], s.y[worst], worst_value};
  std::ostringstream m;
  m << "at t = " << t_ + dt << " s, step " << steps_ + 1 << ", dt = " << dt << " s: ";
  switch (kind) {
    case FailureKind::non_finite:
      failure_site_.value = non_finite;
      m << non_finite << " particle(s) with non-finite state or rates (NaN or inf)";
      break;
    case FailureKind::speed:
      m << "particle speed " << vmax << " mm/s exceeds 0.5 c0 = " << 0.5 * case_.c0()
        << " mm/s (the flow blew up, weak compressibility no longer holds)";
      break;
    case FailureKind::density:
      m << "density deviates by " << 100 * drho_max << "% from rho0 "
        << (steps_ == 0 ? "(at the first step: the starting arrangement of the particles is "
                          "already that far from a uniform one)"
                        : "(the flow blew up)");
      break;
    default:
      m << "concentration left the physical band [0, " << c_max << "] by " << c_dev
        << " mol/m^3 (the species step is unstable)";
      break;
  }
  m << "; worst at the " << kind_of_worst << " particle last at (x, y) = (" << s.x[worst] << ", "
    << s.y[worst] << ") mm.";
  failure_ = m.str();
  return false;
}

}  // namespace adrsph
