#include "particles/particle_store.hpp"

#include <algorithm>
#include <limits>
#include <type_traits>

namespace adrsph {

namespace {
// The cycles of the permutation i -> from(i), fixed points left out: one position of each
// cycle (its leader) is returned; the cycle is walked again from it by following from().
// A re-sort's permutation is a few long cycles (a particle that changes cell shifts every
// particle between its old and new place by one): a list of their positions would cost four
// bytes per particle at every re-sort, the leaders a few bytes in all.
template <class From>
std::vector<std::uint32_t> cycle_leaders(std::size_t n, From from, std::vector<bool>& seen) {
  std::vector<std::uint32_t> leaders;
  seen.assign(n, false);
  for (std::size_t start = 0; start < n; ++start) {
    if (seen[start] || from(start) == start) continue;
    std::size_t j = start;
    do {
      seen[j] = true;
      j = from(j);
    } while (j != start);
    leaders.push_back(static_cast<std::uint32_t>(start));
  }
  return leaders;
}

// a[i] = old a[from(i)], in place: along each cycle every value moves one place, one value
// held aside. No second array: the store is most of a run's memory, and a copy of its largest
// field for a gather cost 13 bytes per particle. A re-sort moves particles within a few cells:
// the cycle steps stay close in memory.
template <class T, class From>
void permute_in_place(std::vector<T>& a, From from, std::span<const std::uint32_t> leaders) {
  for (const std::uint32_t start : leaders) {
    const T held = a[start];
    std::size_t j = start;
    for (std::size_t f = from(j); f != start; f = from(j)) {
      a[j] = a[f];
      j = f;
    }
    a[j] = held;
  }
}
}  // namespace

void ParticleStore::reserve(std::size_t n) {
  for_each_field(*this, [n](auto& a, Role, const char*) { a.reserve(n + 1); });
}

std::size_t ParticleStore::bytes() const {
  std::size_t total = 0;
  auto add = [&total](const auto& a, Role, const char* = nullptr) {
    total += a.capacity() * sizeof(typename std::decay_t<decltype(a)>::value_type);
  };
  for_each_field(*this, add);
  return total;
}

void ParticleStore::resize(std::size_t n) {
  if (n + 1 > x.capacity()) reserve(grown_capacity(n));
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
  if (!n.predicted_density) release(predicted_density);
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
  // Zero in every field (no species, mask off), then:
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
  if (needs_.predicted_density) predicted_density[i] = std::numeric_limits<float>::quiet_NaN();
}

void ParticleStore::permute(std::span<const std::uint32_t> order) {
  // Completed to a permutation of all n particles: the ones not listed (removed) take the
  // places past order.size(), then are cut off.
  const std::size_t n = n_, kept = order.size();
  std::vector<bool> done(n, false);
  for (std::uint32_t i : order) done[i] = true;
  std::vector<std::uint32_t> removed;
  for (std::size_t i = 0; i < n; ++i)
    if (!done[i]) removed.push_back(static_cast<std::uint32_t>(i));
  const auto from = [&](std::size_t j) -> std::size_t {
    return j < kept ? order[j] : removed[j - kept];
  };
  const std::vector<std::uint32_t> leaders = cycle_leaders(n, from, done);
  for_each_field(*this, [&](auto& a, Role role, const char*) {
    if (carried(role)) permute_in_place(a, from, leaders);
    a.resize(kept + 1);  // shrinking: the capacity stays
  });
  n_ = kept;
  reset_padding();
}

}  // namespace adrsph
