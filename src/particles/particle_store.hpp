// Structure-of-arrays particle store. The passes take raw arrays of it; no particle objects.
// One extra "padding" particle lives past the last real one (index size()): so far away that
// every kernel term of a pair with it is zero, and a wall (no diffusion, not sampled by the
// boundaries), so neighbour lists padded with its index contribute nothing.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/simulation.hpp"

namespace adrsph {

struct ParticleStore {
  // State (what the integrator advances or the boundaries prescribe).
  std::vector<double> x, y;        // position [mm]
  std::vector<double> vx, vy;      // fluid velocity u [mm/s]
  std::vector<double> rho;         // density [kg/m^3]
  std::vector<double> c;           // concentration [mol/m^3]
  std::vector<std::uint8_t> kind;  // Kind
  // Derived per evaluation, and the rates: single precision. They are recomputed every
  // evaluation from the double state and only ever enter it multiplied by dt, so their
  // rounding (6e-8 relative) stays far below the discretisation error (perf/README.md,
  // "float storage"); halving them saves 40 bytes per particle.
  std::vector<float> p;  // pressure [kg/m^3 mm^2/s^2 = 1e-6 Pa]
  // V = m / rho [mm^2], in single precision as the passes use it. Computed where it is read,
  // not stored: every pass that sets rho would set V with it (4 bytes per particle).
  static float volume_of(double mass, double rho) { return static_cast<float>(mass / rho); }
  float volume(std::size_t i) const { return volume_of(mass, rho[i]); }
  // 1 where the particle exchanges species by diffusion: fluid and the inflow buffer (the
  // Dirichlet inlet, C = c_in). 0 for walls (no flux through them) and the outflow buffer
  // (zero diffusive flux through the outlet plane: the zero-gradient outlet of
  // docs/benchmark.md, section 1, held exactly because the pair fluxes are antisymmetric).
  // From kind where it is read (the pair records carry it into the force pass).
  static float diffusion_mask_of(std::uint8_t k) {
    return (k == kFluidByte || k == kInletByte) ? 1.0f : 0.0f;
  }
  float diffusion_mask(std::size_t i) const { return diffusion_mask_of(kind[i]); }
  // 1 for fluid and outlet particles (what boundaries sample). Stored, unlike the diffusion
  // mask: the boundary pass gathers it, and g++ does not vectorise a gather of kind bytes.
  std::vector<float> fluid_side;
  // Rates of one evaluation (fluid particles only).
  std::vector<float> ax, ay, drho, dc;
  std::vector<float> sx, sy;  // shifting velocity du (modern scheme), eq. (10)
  // The rates of the first stage of the step, kept for the second (explicit midpoint goes
  // back to the start state, u0 = u_half - dt/2 f0: src/integrator/midpoint.hpp). They are
  // the arrays above of the first evaluation, swapped in (keep_first_stage_rates): no copy.
  std::vector<float> ax_first, ay_first, drho_first, dc_first, sx_first, sy_first;
  // Conventional scheme: sum_j W_ij at the particle's position at the end of the step, which
  // the force pass takes from the same neighbour walk (pass_context.hpp, DensityPrediction);
  // NaN where none was taken (buffers). It follows its particle through a re-sort, so the
  // step after a rebuild needs no summation pass of its own either (SphSolver::rebuild).
  std::vector<float> predicted_density;
  // C at the start of the step, when sub-cycled diffusion changes it after the transport
  // (Needs::species_start): the rates alone cannot undo that step.
  std::vector<double> c_start;
  // The second and later species of a network (Case::more_species), one array each, like c,
  // dc, dc_first and c_start. Needs::more_species of them are in use; the others stay empty.
  static constexpr int kMaxMore = Case::kMaxSpecies - 1;
  std::array<std::vector<double>, kMaxMore> c_more, c_more_start;
  std::array<std::vector<float>, kMaxMore> dc_more, dc_more_first;
  // C of species e of the case (Case::species_at): c for e = 0, else c_more[e - 1].
  std::vector<double>& concentration(int e) { return e == 0 ? c : c_more[e - 1]; }
  const std::vector<double>& concentration(int e) const { return e == 0 ? c : c_more[e - 1]; }

  double mass = 0.0;  // every particle carries m = rho0 dx^2 (per unit depth)

  // Which optional arrays the scheme writes and reads (scheme_traits.hpp): the others stay
  // empty. Set before the store is first sized (set_needs() resizes what it switches on).
  struct Needs {
    bool momentum = true;            // ax, ay and their first-stage copies
    bool continuity = true;          // drho and drho_first
    bool shifting = true;            // sx, sy and their first-stage copies
    int more_species = 0;            // c_more, dc_more and their first-stage/start arrays in use
    bool species_start = false;      // c_start (c_more_start) instead of dc_first (dc_more_first)
    bool predicted_density = false;  // predicted_density (the conventional scheme)
  };
  void set_needs(Needs n);
  const Needs& needs() const { return needs_; }

  std::size_t size() const { return n_; }
  std::size_t padding_index() const { return n_; }

  // Set the number of real particles (arrays get n + 1 entries; the padding particle is reset).
  // Growing past the capacity adds ~3% headroom, not std::vector's doubling: the store is
  // most of the memory of a run. (Capacity never written is not resident: arrays this large
  // are mapped pages of their own.)
  void resize(std::size_t n);
  // The capacity a growth to n particles takes (~3% headroom); arrays sized with the store
  // (the re-sort's order) grow by the same rule.
  static constexpr std::size_t grown_capacity(std::size_t n) { return n + n / 32 + 64; }
  // Make room for n particles (plus the padding one) in every array, exactly.
  void reserve(std::size_t n);
  std::size_t capacity() const { return x.capacity() == 0 ? 0 : x.capacity() - 1; }
  // Heap bytes held by the arrays (capacity).
  std::size_t bytes() const;
  // `c_more`: the values of the other species (Needs::more_species of them; none: 0).
  void push_back(double x, double y, double vx, double vy, double rho, double c, Kind k,
                 std::span<const double> c_more = {});
  // Reorder the real particles: new index i holds old particle order[i]. order.size() may be
  // smaller than size(): particles not listed are removed. Done in place (no scratch array).
  void permute(std::span<const std::uint32_t> order);
  void reset_padding();
  // After the first evaluation of a step: its rates become the first-stage rates, and the
  // arrays they leave take the second evaluation's (a swap of buffers, nothing is copied).
  void keep_first_stage_rates();

  // The field list: every array of the store the scheme needs, once, with its name.
  // reserve, resize, bytes, permute and the checkpoint (snapshot, restore and the file's
  // datasets, which take these names) are derived from it, so a new field is one line here.
  //   state     follows its particle through a re-sort and is kept in checkpoints;
  //   derived   follows its particle, and is set again from the state (the mask, from kind);
  //   per_step  rewritten every evaluation or step before it is read: a re-sort only sizes it.
  // Arrays of needs switched off are not visited: they stay empty.
  enum class Role { state, derived, per_step };
  static constexpr bool carried(Role r) { return r != Role::per_step; }
  template <class Store, class Visit>
  static void for_each_field(Store& s, Visit&& visit) {
    constexpr Role state = Role::state, derived = Role::derived, per_step = Role::per_step;
    visit(s.x, state, "x"), visit(s.y, state, "y"), visit(s.vx, state, "vx");
    visit(s.vy, state, "vy"), visit(s.rho, state, "rho"), visit(s.c, state, "c");
    visit(s.kind, state, "kind");
    static constexpr std::array<const char*, kMaxMore> more_c = {"c_1", "c_2", "c_3"};
    static constexpr std::array<const char*, kMaxMore> more_dc = {"dc_1", "dc_2", "dc_3"};
    for (int e = 0; e < s.needs_.more_species; ++e) visit(s.c_more[e], state, more_c[e]);
    // p is recomputed every evaluation but read before that by particles that have just
    // entered the fluid: kept.
    visit(s.p, state, "p");
    visit(s.fluid_side, derived, "fluid_side");
    // Kept in checkpoints so that a continued run takes the densities an uninterrupted one
    // takes (SphSolver::restore).
    if (s.needs_.predicted_density) visit(s.predicted_density, state, "predicted_density");
    visit(s.dc, per_step, "dc");
    for (int e = 0; e < s.needs_.more_species; ++e) visit(s.dc_more[e], per_step, more_dc[e]);
    if (s.needs_.momentum) visit(s.ax, per_step, "ax"), visit(s.ay, per_step, "ay");
    if (s.needs_.continuity) visit(s.drho, per_step, "drho");
    if (s.needs_.shifting) visit(s.sx, per_step, "sx"), visit(s.sy, per_step, "sy");
    for_each_first_stage_pair(s, [&](auto&, auto& first) { visit(first, per_step, "first"); });
    if (s.needs_.species_start) {
      visit(s.c_start, per_step, "c_start");
      for (int e = 0; e < s.needs_.more_species; ++e) visit(s.c_more_start[e], per_step, "start");
    }
  }
  // Each rate array in use with the array that keeps its first-stage values.
  template <class Store, class Visit>
  static void for_each_first_stage_pair(Store& s, Visit&& visit) {
    if (s.needs_.momentum) visit(s.ax, s.ax_first), visit(s.ay, s.ay_first);
    if (s.needs_.continuity) visit(s.drho, s.drho_first);
    if (s.needs_.shifting) visit(s.sx, s.sx_first), visit(s.sy, s.sy_first);
    if (!s.needs_.species_start) {
      visit(s.dc, s.dc_first);
      for (int e = 0; e < s.needs_.more_species; ++e) visit(s.dc_more[e], s.dc_more_first[e]);
    }
  }
  // Keep the mask in step with kind[i] after a kind change.
  void set_kind(std::size_t i, Kind k) {
    kind[i] = static_cast<std::uint8_t>(k);
    fluid_side[i] = (k == Kind::fluid || k == Kind::outlet) ? 1.0f : 0.0f;
  }

 private:
  std::size_t n_ = 0;
  Needs needs_;
};

}  // namespace adrsph
