// Species diffusion sub-cycled inside a flow step (time.species_subcycling).
// When the explicit diffusion limit is below the flow's own limit (Pe = 10: 7x below the
// acoustic one on the fine lattice), the flow step carries the species without diffusion,
// then the diffusion term of eq. (12) is integrated over the same dt by s-stage RKL2
// super-time-steps (second-order Runge-Kutta-Legendre) on the frozen end-of-step particle
// configuration (Lie splitting; the splitting error is O(dt) with dt the acoustic step, far
// below the physical time scales). The pair weights w_ij = D (V_i + V_j) (r_ij . grad W_ij) /
// (r_ij^2 + eta^2) are computed once per flow step and reused by every stage, which then
// costs one sparse product.
#pragma once

#include <array>
#include <vector>

#include "adrsph/case.hpp"
#include "schemes/pass_context.hpp"

namespace adrsph {

class DiffusionSubcycler {
 public:
  struct Plan {
    int supersteps = 1;  // RKL2 super-steps per flow step
    int stages = 2;      // stages (sparse products) per super-step
  };
  // The plan for `ratio` = dt / (explicit diffusion limit): stable and accurate.
  static Plan plan(double ratio);

  // Integrate dC/dt = sum_j w_ij (C_i - C_j) over dt by RKL2 super-steps for the fluid
  // particles (buffers keep their C), for every species: the weights are computed once with
  // the largest D and scaled by D_s / D_max for each (the plan, set by the largest D, is
  // stable for the smaller ones). With `track`, returns the moles of each species diffused
  // in from the inflow and outflow buffers (sum_i V_i * flux), for the species balance;
  // else 0.
  std::array<double, Case::kMaxSpecies> advance(ParticleStore& s, const PassContext& ctx, double dt,
                                                Plan plan, bool track);

  std::size_t bytes() const { return weight_.capacity() * sizeof(float); }
  // Give the weights and stage arrays back (the end of a run); advance() makes them anew.
  void release() {
    std::vector<float>().swap(weight_);
    for (auto* v : {&y0_, &l0_, &ym1_, &ym2_, &yj_, &rate_}) std::vector<double>().swap(*v);
  }

 private:
  void compute_weights(const ParticleStore& s, const PassContext& ctx);
  double superstep(ParticleStore& s, std::vector<double>& c, double factor, const PassContext& ctx,
                   double dt, int stages, bool track);
  // rate_i = factor sum_j w_ij (c_i - c_j) for fluid i; with `track`, returns
  // sum_i V_i * (exchange with the buffers).
  double rates(const ParticleStore& s, const PassContext& ctx, const std::vector<double>& c,
               double factor, std::vector<double>& rate, bool track) const;

  std::vector<float> weight_;  // one per neighbour-list entry (float halves the memory)
  std::vector<double> y0_, l0_, ym1_, ym2_, yj_, rate_;  // RKL2 stages (one value per particle)
};

}  // namespace adrsph
