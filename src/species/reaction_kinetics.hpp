// The reactions of `[[reaction]]` tables (case.hpp, cases/README.md): each consumes the species
// at a rate R(C) per volume,
//   first_order       R = k C                 C(t) = C0 exp(-k t)
//   nth_order         R = k C^n               C(t)^(1-n) = C0^(1-n) - (1-n) k t   (n != 1;
//                                             for n < 1 the species is used up at finite t)
//   michaelis_menten  R = k C / (km + C)      km ln(C / C0) + C - C0 = -k t
// with k scaled by the factor of the zone that holds the particle, k(x, y) piecewise constant.
// A step integrates each reaction exactly over dt at the particle's position (a particle is a
// small batch reactor); several reactions are applied one after the other, whose splitting
// error (k dt)^2 is ~1e-10 at the steps of a run. The transport step and the reaction step
// are split the same way (sph_solver.cpp, react()).
#pragma once

#include "adrsph/case.hpp"

namespace adrsph {

// k(x, y) / k: the factor of the first zone holding (x, y), 1 outside every zone.
double zone_factor(const Reaction& r, double x, double y);

// C after time t of reaction r alone, from C0 >= 0, with rate constant k_eff (k times the zone
// factor). Exact (michaelis_menten: its implicit solution to round-off, by Newton).
double react_exact(const Reaction& r, double k_eff, double c0, double t);

// C after time t of a batch of the case's kinetics from C0 (species.k and every [[reaction]],
// with zone factor `factor` for all of them): the exact single-reaction updates over 1000
// sub-steps. What a streamline of the plug-flow limit holds (steady_state.cpp's bound).
double batch_concentration(const Case& c, double c0, double t, double factor = 1.0);

}  // namespace adrsph
