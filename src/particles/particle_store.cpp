#include "particles/particle_store.hpp"

#include <algorithm>

namespace adrsph {

namespace {
// Gather a[order[i]] into tmp (which keeps its capacity) and swap it in.
template <class T>
void permute_array(std::vector<T>& a, std::span<const std::uint32_t> order, std::vector<T>& tmp) {
  tmp.resize(order.size() + 1);
  for (std::size_t i = 0; i < order.size(); ++i) tmp[i] = a[order[i]];
  a.swap(tmp);
}

template <class... Arrays>
void resize_all(std::size_t n, Arrays&... arrays) {
  (arrays.resize(n), ...);
}

template <class... Arrays>
void reserve_all(std::size_t n, Arrays&... arrays) {
  (arrays.reserve(n), ...);
}

template <class... Arrays>
std::size_t bytes_of(const Arrays&... arrays) {
  return ((arrays.capacity() * sizeof(typename Arrays::value_type)) + ...);
}
}  // namespace

void ParticleStore::reserve(std::size_t n) {
  reserve_all(n + 1, x, y, vx, vy, rho, c, kind, p, vol, diffusion_mask, fluid_side, ax, ay, drho,
              dc, sx, sy, x0, y0, vx0, vy0, rho0, c0, scratch_, scratch_f_, scratch_k_);
}

std::size_t ParticleStore::bytes() const {
  return bytes_of(x, y, vx, vy, rho, c, kind, p, vol, diffusion_mask, fluid_side, ax, ay, drho, dc,
                  sx, sy, x0, y0, vx0, vy0, rho0, c0, scratch_, scratch_f_, scratch_k_);
}

void ParticleStore::resize(std::size_t n) {
  if (n + 1 > x.capacity()) reserve(n + n / 32 + 64);
  n_ = n;
  resize_all(n + 1, x, y, vx, vy, rho, c, kind, p, vol, diffusion_mask, fluid_side, ax, ay, drho,
             dc, sx, sy, x0, y0, vx0, vy0, rho0, c0);
  reset_padding();
}

void ParticleStore::reset_padding() {
  const std::size_t k = n_;
  x[k] = y[k] = 1e12;  // far beyond any support: W = grad W = 0 for every pair with it
  vx[k] = vy[k] = 0.0;
  rho[k] = 1.0;
  c[k] = 0.0;
  kind[k] = static_cast<std::uint8_t>(Kind::wall);
  p[k] = 0.0f;
  vol[k] = 0.0f;
  diffusion_mask[k] = 0.0f;
  fluid_side[k] = 0.0f;
}

void ParticleStore::push_back(double px, double py, double pvx, double pvy, double prho, double pc,
                              Kind k) {
  const std::size_t i = n_;
  resize(n_ + 1);
  x[i] = px;
  y[i] = py;
  vx[i] = pvx;
  vy[i] = pvy;
  rho[i] = prho;
  c[i] = pc;
  set_kind(i, k);
  p[i] = 0.0f;
  vol[i] = prho > 0 ? static_cast<float>(mass / prho) : 0.0f;
}

void ParticleStore::permute(std::span<const std::uint32_t> order) {
  const std::size_t cap = std::max(x.capacity(), order.size() + 1);
  scratch_.reserve(cap);
  scratch_f_.reserve(cap);
  scratch_k_.reserve(cap);
  for (auto* a : {&x, &y, &vx, &vy, &rho, &c}) permute_array(*a, order, scratch_);
  for (auto* a : {&p, &vol, &diffusion_mask, &fluid_side}) permute_array(*a, order, scratch_f_);
  permute_array(kind, order, scratch_k_);
  n_ = order.size();
  // Rates and saved state are recomputed every step: only their size must follow.
  resize_all(n_ + 1, ax, ay, drho, dc, sx, sy, x0, y0, vx0, vy0, rho0, c0);
  reset_padding();
}

}  // namespace adrsph
