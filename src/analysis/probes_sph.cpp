#include "analysis/probes_sph.hpp"

#include <cmath>
#include <string>

namespace adrsph {

ProbeSampler::FlowSample ProbeSampler::flow_sample_at(double x, double y) const {
  double num = 0.0, flow = 0.0, den = 0.0;
  const double* c = species ? species : particles.c.data();
  grid.for_each_near(x, y, rings, [&](std::uint32_t j) {
    // Every particle that carries species: fluid and both buffers (the outflow buffer
    // holds the C its particles carried through x = L, a zero-gradient continuation).
    if (particles.kind[j] == kWallByte) return;
    const double rx = x - particles.x[j], ry = y - particles.y[j];
    const double w = particles.volume(j) * kernel.value(std::sqrt(rx * rx + ry * ry));
    num += w * c[j];
    flow += w * particles.vx[j];
    den += w;
  });
  if (!(den > 0.0)) return {std::nan(""), std::nan("")};
  return {num / den, flow / den};
}

OutletRow ProbeSampler::outlet_means(double x, double half_width, int n_points) const {
  double cu = 0.0, u = 0.0, c = 0.0;
  for (int k = 0; k < n_points; ++k) {
    const FlowSample s = flow_sample_at(x, -half_width + (k + 0.5) * 2.0 * half_width / n_points);
    cu += s.c * s.ux;
    u += s.ux;
    c += s.c;
  }
  OutletRow row;
  row.c_flow = u != 0.0 ? cu / u : std::nan("");
  row.c_section = c / n_points;
  return row;
}

double ProbeSampler::section_average(double x, double half_width, int n_points) const {
  double sum = 0.0;
  for (int k = 0; k < n_points; ++k)
    sum += concentration_at(x, -half_width + (k + 0.5) * 2.0 * half_width / n_points);
  return sum / n_points;
}

ProbeTable ProbeSampler::probe_lines(double length, double half_width, int n_section) const {
  ProbeTable t;
  t.x_mm = probe_x_positions(length);
  const std::size_t n = t.x_mm.size();
  t.c_y0.resize(n);
  t.c_yp25.resize(n);
  t.c_ym25.resize(n);
  t.c_mean.resize(n);
  const double y_line = 0.5 * half_width;  // the paper's r = +-2.5 mm for R = 5
#pragma omp parallel for schedule(dynamic, 4)
  for (std::size_t i = 0; i < n; ++i) {
    const double x = t.x_mm[i];
    t.c_y0[i] = concentration_at(x, 0.0);
    t.c_yp25[i] = concentration_at(x, y_line);
    t.c_ym25[i] = concentration_at(x, -y_line);
    t.c_mean[i] = section_average(x, half_width, n_section);
  }
  return t;
}

std::string probe_interpolation_text(int n_section) {
  return "Shepard-normalised quintic kernel sum over fluid and buffer particles; section "
         "average = mean of " +
         std::to_string(n_section) + " points evenly spaced over y in [-R, R] (midpoint rule)";
}

}  // namespace adrsph
