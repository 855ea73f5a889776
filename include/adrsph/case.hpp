// The validated description of one run: everything a case file (TOML) says.
// Units are fixed once here, at the case boundary: mm, s, kg/m^3 for density,
// mol/m^3 for C. See cases/README.md for every key.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace adrsph {

enum class Scheme { modern, conventional };
enum class Flow { wcsph, prescribed };
// What drives a WCSPH flow through the channel (`fluid.driving`): the pressure difference
// between inlet and outlet, as in the paper, or a uniform body force equal to the fully
// developed flow's mean pressure gradient, which leaves the pressure (and so the density)
// uniform along the channel (docs/compressibility.md, "Driving the flow by a body force").
enum class Driving { pressure, body_force };
// The inlet concentration in time (`species.feed.shape`): c_in throughout, a step from `base`
// to c_in at t0, a pulse of c_in over [t0, t0 + width) on `base`, or a table of (t, C) points.
enum class FeedShape { constant, step, pulse, table };
// Rate laws of a `[[reaction]]` table, R the moles of each reactant consumed per volume and
// time: first_order R = k C, nth_order R = k C^n, michaelis_menten R = k C / (km + C), all of
// one reactant; bimolecular R = k C_A C_B of two (A + B -> products).
enum class RateLaw { first_order, nth_order, michaelis_menten, bimolecular };

// One `[[reaction]]` table (species/reaction_kinetics.hpp): consumes its reactants at R each
// and makes R of each product.
struct Reaction {
  RateLaw law = RateLaw::first_order;  // `law`
  // `k`: 1/s; (mol/m^3)^(1-n)/s for nth_order; mol/(m^3 s) (v_max) for MM; m^3/(mol s) for
  // bimolecular
  double k = 0.0;
  double order = 1.0;  // `order`, n of nth_order
  double km = 0.0;     // `km` [mol/m^3], Michaelis constant
  // `zones = [[x0, x1, y0, y1, factor], ...]`: k(x, y) = factor k in the first zone that holds
  // (x, y) (x0 <= x < x1, y0 <= y < y1, mm), k outside every zone.
  struct Zone {
    double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0, factor = 1.0;
  };
  std::vector<Zone> zones;
  // `reactants = ["A", "B"]`, `products = ["C"]`: species by name, resolved to indices into
  // Case::species_at() when the case is loaded. Without `reactants`, the first species; one
  // for every law but bimolecular, which takes two different ones.
  std::optional<std::vector<std::string>> reactant_names;  // not given: the first species
  std::vector<std::string> product_names;
  std::vector<int> reactants = {0}, products;

  // A reaction of the first species with no products (the one-species form).
  static Reaction of(RateLaw law, double k, double order = 1.0, double km = 0.0,
                     std::vector<Zone> zones = {}) {
    Reaction r;
    r.law = law;
    r.k = k;
    r.order = order;
    r.km = km;
    r.zones = std::move(zones);
    return r;
  }
};

struct Case {
  std::string name;                // `name`
  std::filesystem::path source;    // the case file it came from (empty when built in code)
  Scheme scheme = Scheme::modern;  // `scheme` = "modern" | "conventional"
  Flow flow = Flow::wcsph;         // `flow` = "wcsph" | "prescribed"

  struct Geometry {
    double length = 100.0;    // `geometry.length` [mm], channel x in [0, length]
    double half_width = 5.0;  // `geometry.half_width` [mm], y in [-R, R]
  } geometry;

  struct Particles {
    double dx = 0.25;       // `particles.dx` [mm], lattice spacing; h = dx
    int wall_layers = 3;    // `particles.wall_layers`, dummy layers (>= 3 for support 3h)
    int inlet_layers = 7;   // `particles.inlet_layers`, inflow buffer depth in dx
    int outlet_layers = 4;  // `particles.outlet_layers`, outflow buffer depth in dx
    double skin = 0.05;     // `particles.skin`, neighbour-list skin as a fraction of 3h
    double jitter = 0.0;    // `particles.jitter`, random start offsets of the fluid, fraction of dx
    // `particles.wall_images`: the species diffusion sum mirrors each neighbour across the
    // wall (method of images, species/wall_images.hpp) instead of only skipping the walls.
    // Both give no flux through the walls; the images also give the first rows their full
    // axial diffusion (docs/physics.md, "Species").
    bool wall_images = false;
    // The skin when a prescribed-flow case does not set one. Its particles move exactly with
    // u(y), so nothing but the list limits their step, and at the default Courant number
    // (0.25) a 0.05 skin is used up every step: lists were rebuilt every step, 63% of the
    // quick default case. At 0.2 they last about 4 steps and the pair loop grows by a fifth:
    // the default case runs 1.75x faster with the same result (perf/README.md, section 3.5).
    static constexpr double kPrescribedSkin = 0.2;
  } particles;

  struct Fluid {
    double rho0 = 1.2;                    // `fluid.rho0` [kg/m^3]
    double nu = 15.0;                     // `fluid.nu` [mm^2/s]
    double u_bulk = 100.0;                // `fluid.u_bulk` [mm/s]; u_max = 2 u_bulk
                                          // (docs/benchmark.md, section 1)
    double c0_factor = 10.0;              // `fluid.c0_factor`, c0 = c0_factor * u_max
    double gamma = 7.0;                   // `fluid.gamma`, Tait exponent
    double background_pressure = 0.025;   // `fluid.background_pressure`, p_b / (rho0 c0^2)
    Driving driving = Driving::pressure;  // `fluid.driving` = "pressure" | "body_force"
  } fluid;

  // The first species: `[species]`, or the first of several `[[species]]` tables (then its
  // keys are name, D, c_in, c_init and feed; species.k and species.ale belong to one species).
  struct Species {
    std::string name = "C";  // `species.name`: names its outputs (probes_<name>.csv, ...)
    double D = 10.0;         // `species.D` [mm^2/s]
    double k = 1.462;        // `species.k` [1/s], first-order reaction rate
    double c_in = 2.0;       // `species.c_in` [mol/m^3], inlet concentration
    double c_init = 2.0;     // `species.c_init` [mol/m^3], initial concentration
    bool ale = false;        // `species.ale`, add du . grad C (consistent ALE form, modern only)
    // `[species.feed]`: the inlet concentration as a function of time (species/inlet_feed.hpp).
    struct Feed {
      FeedShape shape = FeedShape::constant;  // `species.feed.shape`
      double t0 = 0.0;                        // `species.feed.t0` [s], step instant or pulse start
      double width = 0.0;                     // `species.feed.width` [s], pulse width
      double base = 0.0;  // `species.feed.base` [mol/m^3], inlet C before the step, off the pulse
      std::vector<std::array<double, 2>> table;  // `species.feed.table`, [[t, C], ...]
    } feed;
  } species;
  // The second and later `[[species]]` tables (species.k = 0 and species.ale = false for all).
  std::vector<Species> more_species;
  // At most this many species: the particle store holds one array per species, and the fused
  // species loop is written for a fixed number of them (particle_store.hpp).
  static constexpr int kMaxSpecies = 4;
  int species_count() const { return 1 + static_cast<int>(more_species.size()); }
  const Species& species_at(int s) const {
    return s == 0 ? species : more_species[static_cast<std::size_t>(s - 1)];
  }
  Species& species_at(int s) {
    return s == 0 ? species : more_species[static_cast<std::size_t>(s - 1)];
  }

  // `[[reaction]]` tables: reactions besides species.k's first-order one (a case file with
  // `[[reaction]]` tables and no species.k has species.k = 0). Rates add.
  std::vector<Reaction> reactions;

  struct Modern {
    double delta = 0.1;      // `modern.delta`, density diffusion coefficient (eq. 8)
    double shift_eps = 0.5;  // `modern.shift_eps`, shifting coefficient (eq. 10)
    double shift_max = 0.2;  // `modern.shift_max`, cap of the shift per step, fraction of dx
  } modern;

  struct Time {
    double t_end = 10.0;             // `time.t_end` [s]
    long max_steps = 0;              // `time.max_steps`, 0 = no limit
    double cfl = 0.25;               // `time.cfl`, acoustic (or advective) Courant number
    double viscous_number = 0.125;   // `time.viscous_number`, dt <= this * h^2 / nu
    double diffusion_number = 0.25;  // `time.diffusion_number`, dt <= this * h^2 / D
    double dt = 0.0;                 // `time.dt` [s], fixed step; 0 = from the limits
    double dt_factor = 0.0;  // `time.dt_factor`, fixed step = this x the case's limit; 0 = off
    double check_interval = 0.05;    // `time.check_interval` [s], probes + guards + steady test
    bool stop_when_steady = true;    // `time.stop_when_steady`
    double steady_tol = 1e-3;        // `time.steady_tol`, max change of window-mean probes / c_in
    double steady_window = 0.5;      // `time.steady_window` [s], must hold this long
    double steady_sweep_tol = 1e-4;  // `time.steady_sweep_tol`, cold-start transient bound; 0 = off
    double average_window = 0.0;     // `time.average_window` [s], probe time average at the end
    bool warm_start = false;  // `time.warm_start`, start C from the prescribed-flow steady state
    bool species_subcycling =
        true;  // `time.species_subcycling`, sub-cycle diffusion below the flow dt
  } time;

  struct Output {
    std::vector<double> field_times;  // `output.field_times` [s]; the final state is always written
    bool progress = true;             // `output.progress`, progress on stderr (see cases/README.md)
    double checkpoint_minutes = 10.0;  // `output.checkpoint_minutes` [min] of wall time; 0 = never
    // `output.outlet_interval` [s]: sample the outlet (flow-weighted mean C at x = L) into
    // outlet.csv this often; 0 = not written (the residence-time distribution reads it).
    double outlet_interval = 0.0;
  } output;

  double u_max() const { return 2.0 * fluid.u_bulk; }
  double c0() const { return fluid.c0_factor * u_max(); }
  // The body force per mass [mm/s^2] along x with fluid.driving = "body_force": the pressure
  // gradient -dp/dx = 2 mu u_max / R^2 of planar Poiseuille flow, over rho0; 0 otherwise.
  double body_force_x() const {
    if (flow != Flow::wcsph || fluid.driving != Driving::body_force) return 0.0;
    const double r = geometry.half_width;
    return 2.0 * fluid.nu * u_max() / (r * r);
  }
  double h() const { return particles.dx; }
  double peclet() const { return fluid.u_bulk * geometry.length / species.D; }
};

// A bad case file or override. `what()` names the file, the key and what was expected
// ("FILE: key 'K': EXPECTED", or "FILE: EXPECTED" when no key applies, e.g. a syntax error).
class CaseError : public std::runtime_error {
 public:
  CaseError(const std::string& file, const std::string& key, const std::string& expected)
      : std::runtime_error(file + (key.empty() ? "" : ": key '" + key + "'") + ": " + expected),
        file_(file),
        key_(key) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }

 private:
  std::string file_, key_;
};

// Read and validate a case file; `overrides` are "key=value" strings (dotted keys, TOML
// values) applied before validation. Throws CaseError.
Case load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
// The same for the text of a case file; `file` names it in messages and gives the default
// name (the fuzz target, tests/fuzz, reads cases this way).
Case load_case_text(const std::string& text, const std::filesystem::path& file,
                    const std::vector<std::string>& overrides = {});

// Check physical and geometric consistency (D >= 0, dx fits the channel, ...). Throws CaseError.
void validate_case(const Case& c);

const char* to_string(Scheme s);
const char* to_string(Flow f);
const char* to_string(FeedShape f);
const char* to_string(RateLaw r);

}  // namespace adrsph
