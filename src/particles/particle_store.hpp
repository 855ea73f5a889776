// Structure-of-arrays particle store. The passes take raw arrays of it; no particle objects.
// One extra "padding" particle lives past the last real one (index size()): far away, with
// zero volume, so neighbour lists padded with its index contribute nothing.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "adrsph/simulation.hpp"

namespace adrsph {

struct ParticleStore {
  // State (what the integrator advances or the boundaries prescribe).
  std::vector<double> x, y;    // position [mm]
  std::vector<double> vx, vy;  // fluid velocity u [mm/s]
  std::vector<double> rho;     // density [kg/m^3]
  std::vector<double> c;       // concentration [mol/m^3]
  std::vector<std::uint8_t> kind;  // Kind
  // Derived per evaluation.
  std::vector<double> p;        // pressure [kg/m^3 mm^2/s^2 = 1e-6 Pa]
  std::vector<double> vol;      // V = m / rho [mm^2]
  std::vector<double> c_mask;   // 1 where the particle carries species (not a wall), else 0
  std::vector<double> fluid_side;  // 1 for fluid and outlet particles (what boundaries sample)
  // Rates of one evaluation (fluid particles only).
  std::vector<double> ax, ay, drho, dc;
  std::vector<double> sx, sy;  // shifting velocity du (modern scheme), eq. (10)
  // State at the start of the step (explicit midpoint needs it).
  std::vector<double> x0, y0, vx0, vy0, rho0, c0;

  double mass = 0.0;  // every particle carries m = rho0 dx^2 (per unit depth)

  std::size_t size() const { return n_; }
  std::size_t padding_index() const { return n_; }

  // Set the number of real particles (arrays get n + 1 entries; the padding particle is reset).
  void resize(std::size_t n);
  void push_back(double x, double y, double vx, double vy, double rho, double c, Kind k);
  // Reorder the real particles: new index i holds old particle order[i]. order.size() may be
  // smaller than size(): particles not listed are removed.
  void permute(std::span<const std::uint32_t> order);
  // Copy the current state into the *0 arrays.
  void save_state();
  void reset_padding();
  // Keep the masks in step with kind[i] after a kind change.
  void set_kind(std::size_t i, Kind k) {
    kind[i] = static_cast<std::uint8_t>(k);
    c_mask[i] = k == Kind::wall ? 0.0 : 1.0;
    fluid_side[i] = (k == Kind::fluid || k == Kind::outlet) ? 1.0 : 0.0;
  }

 private:
  std::size_t n_ = 0;
};

}  // namespace adrsph
