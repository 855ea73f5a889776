// The laminar-flow-reactor channel (docs/benchmark.md, section 1): fluid lattice in
// [0, L] x [-R, R], dummy wall layers above and below, an inflow buffer upstream of x = 0 fed row
// by row with the parabolic profile and C = c_in, and an outflow buffer downstream of x = L where
// particles keep their velocity and C (zero gradient) until they are removed.
#pragma once

#include <array>
#include <cmath>
#include <span>
#include <vector>

#include "adrsph/case.hpp"
#include "particles/particle_store.hpp"

namespace adrsph {

// Particles of the initial state of case `c` (initial_count()), computed in double without
// building the scene, so that a spacing far too small for any memory gives a large number
// instead of an overflow (the start-up check of `adrsph run`, src/cli/run_preflight.cpp).
double channel_particle_estimate(const Case& c);

class ChannelScene {
 public:
  explicit ChannelScene(const Case& c);

  // u(y) = u_max (1 - (y/R)^2), eq. (13)
  double inflow_velocity(double y) const {
    const double eta = y / half_width_;
    return u_max_ * (1.0 - eta * eta);
  }

  // Fill the store with the initial state: C = c_init, velocity = the analytic profile; fluid
  // particles offset from their lattice sites by up to particles.jitter dx in x and y
  // (uniform, fixed seed: the same start every time).
  void initialise(ParticleStore& s) const;
  // The initial particles of initialise(), in its order, without a store: emit(x, y, kind).
  template <class Emit>
  void for_each_initial(Emit&& emit) const;
  std::size_t initial_count() const;

  // Bounding box that holds every particle that is not lost (for the cell grid).
  double xmin() const { return wall_x0_; }
  double xmax() const { return wall_x1_ + 2 * dx_; }
  double ymin() const { return -half_width_ - wall_layers_ * dx_; }
  double ymax() const { return half_width_ + wall_layers_ * dx_; }

  // Move the inflow row generators with the rows (called every step).
  void advance_inflow(double dt);
  // Particles that crossed the inlet plane (inlet -> fluid) and the outlet plane
  // (fluid -> outlet), with the species they carried (sum of V C, per species).
  struct Crossings {
    long entered = 0, left = 0;
    std::array<double, Case::kMaxSpecies> species_in{}, species_out{};
  };
  // Kind changes that keep indices: inlet -> fluid at x >= 0, fluid -> outlet at x >= L.
  Crossings update_kinds(ParticleStore& s) const;
  // At a re-sort: feed new inlet particles and mark particles to remove with x = NaN (the
  // sort then drops them): outlet particles past the buffer and fluid particles that left
  // through a wall or the inlet (those are counted in `lost`).
  void feed_and_drain(ParticleStore& s, long& lost);

  // The inflow row generators (checkpoint/restart).
  const std::vector<double>& inflow_row_tails() const { return row_tail_x_; }
  void set_inflow_row_tails(std::vector<double> tails);

  // The C of species s given to inlet particles fed from now on (a feed that varies in time).
  void set_inlet_concentration(int species, double c) {
    c_in_[static_cast<std::size_t>(species)] = c;
  }

  double length() const { return length_; }
  double half_width() const { return half_width_; }

 private:
  using PerSpecies = std::array<double, Case::kMaxSpecies>;
  // The values of the second and later species (ParticleStore::push_back's c_more).
  std::span<const double> more(const PerSpecies& v) const {
    return std::span<const double>(v).subspan(1, more_species_);
  }
  double dx_, length_, half_width_, u_max_, rho0_, jitter_;
  PerSpecies c_in_{}, c_init_{};  // inlet and initial C of every species
  std::size_t more_species_ = 0;
  int wall_layers_, inlet_layers_, outlet_layers_;
  double wall_x0_, wall_x1_;
  std::vector<double> row_y_;       // inflow rows
  std::vector<double> row_tail_x_;  // x of the most upstream inlet particle of each row
};

template <class Emit>
void ChannelScene::for_each_initial(Emit&& emit) const {
  const int nx = static_cast<int>(std::lround(length_ / dx_));
  for (double yr : row_y_) {
    for (int i = 0; i < inlet_layers_; ++i) emit(-(i + 0.5) * dx_, yr, Kind::inlet);
    for (int i = 0; i < nx; ++i) emit((i + 0.5) * dx_, yr, Kind::fluid);
    for (int i = 0; i < outlet_layers_; ++i) emit(length_ + (i + 0.5) * dx_, yr, Kind::outlet);
  }
  const int nwx = static_cast<int>(std::lround((wall_x1_ - wall_x0_) / dx_));
  for (int k = 0; k < wall_layers_; ++k) {
    const double yw = half_width_ + (k + 0.5) * dx_;
    for (int i = 0; i < nwx; ++i) {
      const double xw = wall_x0_ + (i + 0.5) * dx_;
      emit(xw, yw, Kind::wall);
      emit(xw, -yw, Kind::wall);
    }
  }
}

}  // namespace adrsph
