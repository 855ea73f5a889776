// Species diffusion next to a flat wall by the method of images (`particles.wall_images`).
//
// The walls carry no species, and eq. (12)'s diffusion sum skips them: no flux crosses the
// wall, but a particle next to it also misses the pairs its wall neighbours would have given
// along the wall. On the lattice the first row's axial Laplacian is 0.774 of the exact value
// and the second's 0.987, against 0.994 inside (Operators.DiffusionNextToAWall*): at coarse
// resolution the channel's section-averaged axial diffusivity is about 2.9% low.
//
// A zero normal flux at a flat wall y = y_w is the mirror symmetry C(x, y_w + s) = C(x, y_w - s).
// Each species-carrying neighbour j of a fluid particle i then has an image j* at
// (x_j, 2 y_w - y_j) with C_j* = C_j and V_j* = V_j, and the pair (i, j*) adds
//     D (V_i + V_j) lap_weight(|r_i - r_j*|) (C_i - C_j)
// to dC_i/dt. The image of j seen from i and that of i seen from j lie at the same distance
// (the mirror is an isometry), so the two terms are equal and opposite: the sum still conserves
// the species exactly, and the wall still passes no flux. An image is never nearer than its
// original, so every image pair within the support comes from a pair of the neighbour list.
// Each particle is mirrored across the wall on its own side (y_i >= 0: y = +R); validation
// requires R > 3h so that the other wall's images are out of reach.
#pragma once

#include <cmath>

#include "schemes/pass_context.hpp"

namespace adrsph {

// |r_i - r_j*|^2 for the image of j across the wall on i's side, walls at y = +-wall_y.
inline double wall_image_r2(double dx, double yi, double yj, double wall_y) {
  const double yw = yi >= 0.0 ? wall_y : -wall_y;
  const double dy = yi + yj - 2.0 * yw;  // y_i - (2 y_w - y_j)
  return dx * dx + dy * dy;
}

// Adds the image pairs' diffusion to dC/dt (ParticleStore::dc, and dc_more for a network) of
// the fluid particles within the kernel support of a wall: the complement of the fused force
// pass (interaction_pass.hpp) when `phys.wall_image_y > 0`.
void add_wall_image_diffusion(ParticleStore& s, const PassContext& ctx);

}  // namespace adrsph
