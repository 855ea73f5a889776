#include "particles/particle_store.hpp"

#include <algorithm>
#include <type_traits>

namespace adrsph {

namespace {
// Gather a[order[i]] into tmp (which keeps its capacity) and swap it in.
template <class T>
void permute_array(std::vector<T>& a, std::span<const std::uint32_t> order, std::vector<T>& tmp) {
  tmp.resize(order.size() + 1);
  for (std::size_t i = 0; i < order.size(); ++i) tmp[i] = a[order[i]];
  a.swap(tmp);
}
}  // namespace

void ParticleStore::reserve(std::size_t n) {
  for_each_field(*this, [n](auto& a, Role, const char*) { a.reserve(n + 1); });
  scratch_.reserve(n + 1);
  scratch_f_.reserve(n + 1);
  scratch_k_.reserve(n + 1);
}

std::size_t ParticleStore::bytes() const {
  std::size_t total = 0;
  auto add = [&total](const auto& a, Role, const char* = nullptr) {
    total += a.capacity() * sizeof(typename std::decay_t<decltype(a)>::value_type);
  };
  for_each_field(*this, add);
  add(scratch_, Role::per_step);
  add(scratch_f_, Role::per_step);
  add(scratch_k_, Role::per_step);
  return total;
}

void ParticleStore::resize(std::size_t n) {
  if (n + 1 > x.capacity()) reserve(n + n / 32 + 64);
  n_ = n;
  for_each_field(*this, [n](auto& a, Role, const char*) { a.resize(n + 1); });
  reset_padding();
}

void ParticleStore::set_needs(Needs n) {
  // Free what is switched off, then size what is on (resize skips nothing it visits).
  auto release = [](auto& a) { std::decay_t<decltype(a)>().swap(a); };
  if (!n.momentum) release(ax), release(ay), release(ax_first), release(ay_first);
  if (!n.continuity) release(drho), release(drho_first);
  if (!n.shifting) release(sx), release(sy), release(sx_first), release(sy_first);
  if (n.species_start) release(dc_first);
  if (!n.species_start) release(c_start);
  for (int e = 0; e < kMaxMore; ++e) {
    const bool used = e < n.more_species;
    if (!used) release(c_more[e]), release(dc_more[e]);
    if (!used || n.species_start) release(dc_more_first[e]);
    if (!used || !n.species_start) release(c_more_start[e]);
  }
  needs_ = n;
  const std::size_t cap = capacity();
  reserve(cap);
  resize(n_);
}

void ParticleStore::keep_first_stage_rates() {
  for_each_first_stage_pair(*this, [](auto& rate, auto& first) { rate.swap(first); });
}

void ParticleStore::reset_padding() {
  const std::size_t k = n_;
  // Zero in every field (no volume, no species, masks off), then:
  for_each_field(*this, [k](auto& a, Role, const char*) { a[k] = {}; });
  x[k] = y[k] = 1e12;  // far beyond any support: W = grad W = 0 for every pair with it
  rho[k] = 1.0;
  kind[k] = kWallByte;
}

void ParticleStore::push_back(double px, double py, double pvx, double pvy, double prho, double pc,
                              Kind k, std::span<const double> pc_more) {
  const std::size_t i = n_;
  resize(n_ + 1);
  for (int e = 0; e < needs_.more_species; ++e)
    c_more[e][i] = static_cast<std::size_t>(e) < pc_more.size() ? pc_more[e] : 0.0;
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
  n_ = order.size();
  for_each_field(*this, [&](auto& a, Role role, const char*) {
    if (!carried(role)) {
      a.resize(n_ + 1);
      return;
    }
    using T = typename std::decay_t<decltype(a)>::value_type;
    if constexpr (std::is_same_v<T, double>)
      permute_array(a, order, scratch_);
    else if constexpr (std::is_same_v<T, float>)
      permute_array(a, order, scratch_f_);
    else
      permute_array(a, order, scratch_k_);
  });
  reset_padding();
}

}  // namespace adrsph
