// SPH values at probe points: Shepard-normalised kernel interpolation over the particles
// that carry species (fluid and buffers, not walls):
//   C(x_p) = sum_j V_j C_j W(x_p - x_j) / sum_j V_j W(x_p - x_j)
// Section averages: the mean of such values at n points evenly spread over y in [-R, R]
// (midpoint rule); the flow-weighted mean of the outlet weights them with u_x interpolated
// the same way.
#pragma once

#include "adrsph/probes.hpp"
#include "kernels/quintic_kernel.hpp"
#include "neighbours/cell_grid.hpp"
#include "particles/particle_store.hpp"

namespace adrsph {

struct ProbeSampler {
  const ParticleStore& particles;
  const CellGrid& grid;  // the grid of the last sort (particles may have moved since)
  const QuinticKernel& kernel;
  // Rings of cells searched around a probe: enough for a particle that has moved since the
  // sort to be found (SphSolver::sampler()). Sampling never re-sorts: watching a run does not
  // change it.
  int rings = 1;
  // The species sampled: one of the store's concentration arrays (nullptr: particles.c).
  const double* species = nullptr;

  // C and the streamwise velocity at a point, with the same weights.
  struct FlowSample {
    double c = 0.0, ux = 0.0;
  };
  FlowSample flow_sample_at(double x, double y) const;
  double concentration_at(double x, double y) const { return flow_sample_at(x, y).c; }
  // The outlet row of outlet.csv at x (adrsph/probes.hpp): flow-weighted mean
  // sum_k ux_k C_k / sum_k ux_k and plain mean of C over the section-average points.
  OutletRow outlet_means(double x, double half_width, int n_points) const;
  double section_average(double x, double half_width, int n_points) const;
  ProbeTable probe_lines(double length, double half_width, int n_section) const;
};

std::string probe_interpolation_text(int n_section);

}  // namespace adrsph
