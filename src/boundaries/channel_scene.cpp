#include "boundaries/channel_scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace adrsph {

namespace {
constexpr std::uint64_t kJitterSeed = 20260101;  // particles.jitter: one fixed start
}  // namespace

ChannelScene::ChannelScene(const Case& c)
    : dx_(c.particles.dx),
      length_(c.geometry.length),
      half_width_(c.geometry.half_width),
      u_max_(c.u_max()),
      rho0_(c.fluid.rho0),
      jitter_(c.particles.jitter),
      wall_layers_(c.particles.wall_layers),
      inlet_layers_(c.particles.inlet_layers),
      outlet_layers_(c.particles.outlet_layers) {
  for (int sp = 0; sp < c.species_count(); ++sp) {
    c_in_[static_cast<std::size_t>(sp)] = c.species_at(sp).c_in;
    c_init_[static_cast<std::size_t>(sp)] = c.species_at(sp).c_init;
  }
  more_species_ = static_cast<std::size_t>(c.species_count() - 1);
  wall_x0_ = -(inlet_layers_ + wall_layers_) * dx_;
  wall_x1_ = length_ + (outlet_layers_ + wall_layers_) * dx_;
  const int ny = static_cast<int>(std::lround(2.0 * half_width_ / dx_));
  for (int j = 0; j < ny; ++j) row_y_.push_back(-half_width_ + (j + 0.5) * dx_);
  row_tail_x_.assign(ny, -(inlet_layers_ - 0.5) * dx_);
}

double channel_particle_estimate(const Case& c) {
  const auto& p = c.particles;
  const double rows = std::round(2.0 * c.geometry.half_width / p.dx);
  const double columns = std::round(c.geometry.length / p.dx);
  const double buffers = static_cast<double>(p.inlet_layers) + p.outlet_layers;
  // Fluid and buffer rows, then the wall layers above and below, which span the buffers too.
  return rows * (columns + buffers) +
         2.0 * p.wall_layers * (columns + buffers + 2.0 * p.wall_layers);
}

std::size_t ChannelScene::initial_count() const {
  std::size_t n = 0;
  for_each_initial([&](double, double, Kind) { ++n; });
  return n;
}

void ChannelScene::initialise(ParticleStore& s) const {
  s.resize(0);
  s.mass = rho0_ * dx_ * dx_;
  // Room for 3% more particles than the lattice: the fluid compresses as the pressure
  // gradient builds up (+0.4% particles at fine resolution in a pressure-driven start). A
  // store that grows in a run moves its arrays one by one and keeps ~one array more resident
  // (+0.5 MB at fine resolution, measured); room never written costs no resident memory.
  const std::size_t n = initial_count();
  s.reserve(n + n / 32 + 2 * row_y_.size());
  std::mt19937_64 rng(kJitterSeed);
  std::uniform_real_distribution<double> offset(-jitter_ * dx_, jitter_ * dx_);
  for_each_initial([&](double x, double y, Kind k) {
    switch (k) {
      case Kind::inlet:
        s.push_back(x, y, inflow_velocity(y), 0.0, rho0_, c_in_[0], k, more(c_in_));
        break;
      case Kind::wall:
        s.push_back(x, y, 0.0, 0.0, rho0_, 0.0, k);
        break;
      case Kind::fluid:
        if (jitter_ > 0.0) {
          x += offset(rng);
          y += offset(rng);
        }
        s.push_back(x, y, inflow_velocity(y), 0.0, rho0_, c_init_[0], k, more(c_init_));
        break;
      default:
        s.push_back(x, y, inflow_velocity(y), 0.0, rho0_, c_init_[0], k, more(c_init_));
        break;
    }
  });
}

void ChannelScene::set_inflow_row_tails(std::vector<double> tails) {
  if (tails.size() != row_tail_x_.size())
    throw std::invalid_argument("the checkpoint has " + std::to_string(tails.size()) +
                                " inflow rows, the case " + std::to_string(row_tail_x_.size()));
  row_tail_x_ = std::move(tails);
}

void ChannelScene::advance_inflow(double dt) {
  for (std::size_t r = 0; r < row_y_.size(); ++r) row_tail_x_[r] += inflow_velocity(row_y_[r]) * dt;
}

ChannelScene::Crossings ChannelScene::update_kinds(ParticleStore& s) const {
  const std::size_t n = s.size();
  const double length = length_;
  const int count = 1 + s.needs().more_species;
  long entered = 0, left = 0;
  double in[Case::kMaxSpecies] = {}, out[Case::kMaxSpecies] = {};
#pragma omp parallel for schedule(static) reduction(+ : entered, left, in[:Case::kMaxSpecies], \
                                                        out[:Case::kMaxSpecies])
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Kind>(s.kind[i]);
    if (k == Kind::inlet && s.x[i] >= 0.0) {
      s.set_kind(i, Kind::fluid);
      ++entered;
      for (int e = 0; e < count; ++e) in[e] += s.mass / s.rho[i] * s.concentration(e)[i];
    }
    if (k == Kind::fluid && s.x[i] >= length) {
      s.set_kind(i, Kind::outlet);
      ++left;
      for (int e = 0; e < count; ++e) out[e] += s.mass / s.rho[i] * s.concentration(e)[i];
    }
  }
  Crossings c{entered, left, {}, {}};
  std::copy_n(in, Case::kMaxSpecies, c.species_in.begin());
  std::copy_n(out, Case::kMaxSpecies, c.species_out.begin());
  return c;
}

void ChannelScene::feed_and_drain(ParticleStore& s, long& lost) {
  const double x_drop = length_ + outlet_layers_ * dx_;
  const double x_lost = -inlet_layers_ * dx_;
  const std::size_t n = s.size();
  const double removed = std::nan("");
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Kind>(s.kind[i]);
    if (k == Kind::outlet && (s.x[i] > x_drop || std::fabs(s.y[i]) > half_width_)) s.x[i] = removed;
    if (k == Kind::fluid && (std::fabs(s.y[i]) > half_width_ || s.x[i] < x_lost ||
                             !std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))) {
      s.x[i] = removed;
      ++lost;
    }
  }
  // Feed: keep the most upstream inlet particle of each row within one dx of the buffer end.
  const double x_first = -(inlet_layers_ - 0.5) * dx_;
  for (std::size_t r = 0; r < row_y_.size(); ++r) {
    while (row_tail_x_[r] - dx_ >= x_first - 1e-9 * dx_) {
      row_tail_x_[r] -= dx_;
      s.push_back(row_tail_x_[r], row_y_[r], inflow_velocity(row_y_[r]), 0.0, rho0_, c_in_[0],
                  Kind::inlet, more(c_in_));
    }
  }
}

}  // namespace adrsph
