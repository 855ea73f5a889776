// The reactions of `[[reaction]]` tables (case.hpp, cases/README.md): each consumes the species
// at a rate R(C) per volume,
//   first_order       R = k C                 C(t) = C0 exp(-k t)
//   nth_order         R = k C^n               C(t)^(1-n) = C0^(1-n) - (1-n) k t   (n != 1;
//                                             for n < 1 the species is used up at finite t)
//   michaelis_menten  R = k C / (km + C)      km ln(C / C0) + C - C0 = -k t
//   bimolecular       R = k C_A C_B           A(t) = A0 / (1 + B0 phi), phi = (1 - e^{-k Delta t})
//                                             / Delta, Delta = A0 - B0 (phi = k t at Delta = 0);
//                                             B - A stays B0 - A0
// with k scaled by the factor of the zone that holds the particle, k(x, y) piecewise constant.
// A step integrates each reaction exactly over dt at the particle's position (a particle is a
// small batch reactor); several reactions are applied one after the other, whose splitting
// error (k dt)^2 is ~1e-10 at the steps of a run. The transport step and the reaction step
// are split the same way (sph_solver.cpp, react()). In a network (several species), what a
// reaction takes from each reactant it adds to each product.
#pragma once

#include <span>
#include <vector>

#include "adrsph/case.hpp"

namespace adrsph {

// k(x, y) / k: the factor of the first zone holding (x, y), 1 outside every zone.
double zone_factor(const Reaction& r, double x, double y);

// C after time t of reaction r alone, from C0 >= 0, with rate constant k_eff (k times the zone
// factor). Exact (michaelis_menten: its implicit solution to round-off, by Newton).
double react_exact(const Reaction& r, double k_eff, double c0, double t);

// Moles per volume of each reactant that a bimolecular reaction A + B -> ... consumes over
// time t from A0, B0 >= 0 with rate constant k_eff, exact (see above; expm1 keeps it exact as
// Delta -> 0).
double bimolecular_extent(double k_eff, double a0, double b0, double t);

// One step dt of every reaction of the case on the concentrations `conc` (one per species,
// Case::species_at order) of a particle at (x, y): species.k's decay of the first species,
// then each [[reaction]] in turn, exact, moving what it consumes to its products.
void react_network(const Case& c, double x, double y, std::span<double> conc, double dt);

// The concentrations after time t of a batch of the case's network from `c0` (one per
// species), at the point (0, 0): react_network over 1000 sub-steps. A bound that leaves the
// zones out passes a copy of the case without them.
std::vector<double> batch_state(const Case& c, std::vector<double> c0, double t);

// C after time t of a batch of the case's kinetics from C0 (species.k and every [[reaction]],
// with zone factor `factor` for all of them): the exact single-reaction updates over 1000
// sub-steps. What a streamline of the plug-flow limit holds (steady_state.cpp's bound).
double batch_concentration(const Case& c, double c0, double t, double factor = 1.0);

}  // namespace adrsph
