// Assembly of the first-order upwind system (docs/benchmark.md, section 5): see
// finite_volume.hpp for the cell balance. Triplets, then one compressed sparse matrix.
#include <stdexcept>

#include "reference/finite_volume.hpp"

namespace adrsph::reference::detail {

std::vector<double> cell_average_velocity(const Problem& p, const Grid& g) {
  std::vector<double> u(static_cast<std::size_t>(g.ny));
  const double dy = g.dy();
  for (int j = 0; j < g.ny; ++j) {
    const double yc = g.yc(j);
    u[j] = (p.velocity(yc - 0.5 * dy) + 4.0 * p.velocity(yc) + p.velocity(yc + 0.5 * dy)) / 6.0;
    if (!(u[j] > 0.0))
      throw std::invalid_argument("reference: velocity must be > 0 in every cell (advection +x)");
  }
  return u;
}

UpwindSystem assemble_upwind_system(const Problem& p, const Grid& g,
                                    const std::vector<double>& u_cell) {
  const double dx = g.dx(), dy = g.dy(), vol = dx * dy;
  const double gx = p.D * dy / dx;  // diffusive conductance of an x-face
  const double gy = p.D * dx / dy;  // of a y-face
  UpwindSystem sys;
  sys.b = Eigen::VectorXd::Zero(g.cells());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(g.cells()) * 5);

  for (int i = 0; i < g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      const long P = g.index(i, j);
      const double f = u_cell[j] * dy;  // advective mass flux through the x-faces of row j
      double diag = (p.k + reaction_slope(p, g.xc(i), g.yc(j))) * vol;
      double rhs = p.source ? p.source(g.xc(i), g.yc(j)) * vol : 0.0;

      // West face: upwind neighbour, or the Dirichlet inlet (value and half-cell gradient).
      diag += f;  // outflow through the east face carries C_P (upwind; zero gradient at outlet)
      if (i > 0) {
        t.emplace_back(P, g.index(i - 1, j), -f - gx);
        diag += gx;
      } else {
        const double c0 = p.inlet_value(g.yc(j));
        rhs += f * c0 + 2.0 * gx * c0;
        diag += 2.0 * gx;
      }
      // East face: diffusion to the neighbour; none through the outlet (zero gradient).
      if (i + 1 < g.nx) {
        t.emplace_back(P, g.index(i + 1, j), -gx);
        diag += gx;
      }
      // South and north faces: diffusion; the walls carry no flux.
      if (j > 0) {
        t.emplace_back(P, g.index(i, j - 1), -gy);
        diag += gy;
      }
      if (j + 1 < g.ny) {
        t.emplace_back(P, g.index(i, j + 1), -gy);
        diag += gy;
      }
      t.emplace_back(P, P, diag);
      sys.b[P] = rhs;
    }
  }
  sys.A.resize(g.cells(), g.cells());
  sys.A.setFromTriplets(t.begin(), t.end());
  sys.A.makeCompressed();
  return sys;
}

}  // namespace adrsph::reference::detail
