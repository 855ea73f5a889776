#include "particles/particle_store.hpp"

#include <algorithm>

namespace adrsph {

namespace {
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
}  // namespace

void ParticleStore::resize(std::size_t n) {
  n_ = n;
  resize_all(n + 1, x, y, vx, vy, rho, c, kind, p, vol, c_mask, fluid_side, ax, ay, drho, dc, sx, sy, x0, y0,
             vx0, vy0, rho0, c0);
  reset_padding();
}

void ParticleStore::reset_padding() {
  const std::size_t k = n_;
  x[k] = y[k] = 1e12;  // far beyond any support: W = grad W = 0 for every pair with it
  vx[k] = vy[k] = 0.0;
  rho[k] = 1.0;
  c[k] = 0.0;
  kind[k] = static_cast<std::uint8_t>(Kind::wall);
  p[k] = 0.0;
  vol[k] = 0.0;
  c_mask[k] = 0.0;
  fluid_side[k] = 0.0;
}

void ParticleStore::push_back(double px, double py, double pvx, double pvy, double prho,
                              double pc, Kind k) {
  const std::size_t i = n_;
  resize(n_ + 1);
  x[i] = px;
  y[i] = py;
  vx[i] = pvx;
  vy[i] = pvy;
  rho[i] = prho;
  c[i] = pc;
  set_kind(i, k);
  p[i] = 0.0;
  vol[i] = prho > 0 ? mass / prho : 0.0;
}

void ParticleStore::permute(std::span<const std::uint32_t> order) {
  std::vector<double> tmp;
  for (auto* a : {&x, &y, &vx, &vy, &rho, &c, &p, &vol, &c_mask, &fluid_side}) permute_array(*a, order, tmp);
  std::vector<std::uint8_t> tmpk;
  permute_array(kind, order, tmpk);
  n_ = order.size();
  // Rates and saved state are recomputed every step: only their size must follow.
  resize_all(n_ + 1, ax, ay, drho, dc, sx, sy, x0, y0, vx0, vy0, rho0, c0);
  reset_padding();
}

void ParticleStore::save_state() {
  std::copy(x.begin(), x.end(), x0.begin());
  std::copy(y.begin(), y.end(), y0.begin());
  std::copy(vx.begin(), vx.end(), vx0.begin());
  std::copy(vy.begin(), vy.end(), vy0.begin());
  std::copy(rho.begin(), rho.end(), rho0.begin());
  std::copy(c.begin(), c.end(), c0.begin());
}

}  // namespace adrsph
