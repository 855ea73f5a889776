// validate_case: every range and consistency rule of a case, with messages that say the range.
#include "case/case_validate.hpp"

#include <cmath>
#include <sstream>

namespace adrsph {
namespace case_detail {
namespace {

std::string num(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}

// Collects the first failed rule; later rules are skipped once one failed.
class Checker {
 public:
  std::optional<Problem> problem;

  void require(bool ok, const std::string& key, const std::string& expected) {
    if (!problem && !ok) problem = Problem{key, expected};
  }
  // v in an interval; `lo_open`/`hi_open` make the ends exclusive. NaN and inf never pass.
  void range(const std::string& key, double v, double lo, bool lo_open, double hi, bool hi_open) {
    const bool ok =
        std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    std::string r;
    if (std::isinf(hi))
      r = lo_open ? "> " + num(lo) : ">= " + num(lo);
    else
      r = "in " + std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) +
          (hi_open ? ")" : "]");
    require(ok, key, "expected a value " + r + ", got " + num(v));
  }
  void positive(const std::string& key, double v) { range(key, v, 0.0, true, kInf, false); }
  void non_negative(const std::string& key, double v) { range(key, v, 0.0, false, kInf, false); }
  // Rows of particles: at least what the kernel support needs, at most kMaxLayers (more
  // only cost memory, and the count must not overflow).
  void layers(const std::string& key, long v, long lo) {
    require(v >= lo && v <= kMaxLayers, key,
            "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(kMaxLayers) +
                "], got " + std::to_string(v));
  }
  static constexpr long kMaxLayers = 100;

  static constexpr double kInf = std::numeric_limits<double>::infinity();
};

// Largest concentration or pressure scale the single-precision particle state carries with
// room for the sums it enters.
constexpr double kMaxStateValue = 1e20;

bool valid_name(const std::string& n) {
  // At most 200 characters: the output directory <name>.partial must fit a file name (255).
  if (n.empty() || n.size() > 200 || n.front() == '.' || n.front() == '-') return false;
  for (const char ch : n) {
    const auto u = static_cast<unsigned char>(ch);
    if (!(std::isalnum(u) || ch == '_' || ch == '-' || ch == '.' || ch == '+')) return false;
  }
  return true;
}

// Number of dx in `extent` when it is an integer (1e-9 relative), else -1.
double cells(double extent, double dx) {
  const double n = extent / dx;
  if (!std::isfinite(n)) return -1.0;
  return std::abs(n - std::round(n)) <= 1e-9 * std::max(1.0, n) ? std::round(n) : -1.0;
}

void check_geometry(Checker& k, const Case& c) {
  k.positive("geometry.length", c.geometry.length);
  k.positive("geometry.half_width", c.geometry.half_width);
  k.positive("particles.dx", c.particles.dx);
  if (k.problem) return;
  const double dx = c.particles.dx;
  k.require(cells(c.geometry.length, dx) > 0, "particles.dx",
            "expected a spacing that divides geometry.length = " + num(c.geometry.length) +
                " into a whole number of particles, got dx = " + num(dx) +
                " (length/dx = " + num(c.geometry.length / dx) + ")");
  const double across = cells(2.0 * c.geometry.half_width, dx);
  k.require(across > 0, "particles.dx",
            "expected a spacing that divides the width 2*half_width = " +
                num(2.0 * c.geometry.half_width) + " into a whole number of particles, got dx = " +
                num(dx) + " (2*half_width/dx = " + num(2.0 * c.geometry.half_width / dx) + ")");
  k.require(across >= 4, "particles.dx",
            "expected at least 4 particles across the channel (dx <= half_width/2 = " +
                num(c.geometry.half_width / 2.0) + "), got dx = " + num(dx));
  k.layers("particles.wall_layers", c.particles.wall_layers, 3);
  k.layers("particles.inlet_layers", c.particles.inlet_layers, 4);
  k.layers("particles.outlet_layers", c.particles.outlet_layers, 3);
  k.range("particles.skin", c.particles.skin, 0.0, false, 1.0, false);
  // Below half a spacing no particle leaves the channel or passes its neighbour's site.
  k.range("particles.jitter", c.particles.jitter, 0.0, false, 0.45, false);
  // Each particle is mirrored across the wall on its own side only; the other wall's images
  // are out of reach when the half width exceeds the kernel support 3h (h = dx).
  k.require(!c.particles.wall_images || c.geometry.half_width > 3.0 * dx, "particles.wall_images",
            "expected false unless half_width > 3 dx (the kernel support; got half_width = " +
                num(c.geometry.half_width) + ", dx = " + num(dx) +
                "): the images of both walls would overlap");
}

void check_fluid_species(Checker& k, const Case& c) {
  k.positive("fluid.rho0", c.fluid.rho0);
  k.positive("fluid.nu", c.fluid.nu);
  k.positive("fluid.u_bulk", c.fluid.u_bulk);
  k.positive("fluid.c0_factor", c.fluid.c0_factor);
  // Tait exponents of real fluids lie in [1, 7]; above 20, (rho/rho0)^gamma turns the
  // density noise of a weakly compressible flow into pressures that overflow.
  k.range("fluid.gamma", c.fluid.gamma, 1.0, false, 20.0, false);
  // A fraction of rho0 c0^2; above 10 the pressure differences of the flow (~1e-2 rho0 c0^2)
  // sink below the single-precision resolution of p + p_b.
  k.range("fluid.background_pressure", c.fluid.background_pressure, 0.0, false, 10.0, false);
  k.non_negative("species.D", c.species.D);
  k.non_negative("species.k", c.species.k);
  // The particle state is single precision (largest value 3.4e38): concentrations and the
  // pressure scale enter sums multiplied by kernel gradients (~1/dx^3) and D or nu.
  k.range("species.c_in", c.species.c_in, 0.0, false, kMaxStateValue, false);
  k.range("species.c_init", c.species.c_init, 0.0, false, kMaxStateValue, false);
  if (k.problem) return;
  const double pressure_scale = c.fluid.rho0 * c.c0() * c.c0();
  // Name the factor that makes it large.
  const char* culprit = c.fluid.rho0 >= c.c0() * c.c0()             ? "fluid.rho0"
                        : c.fluid.c0_factor >= 2.0 * c.fluid.u_bulk ? "fluid.c0_factor"
                                                                    : "fluid.u_bulk";
  k.require(pressure_scale <= kMaxStateValue, culprit,
            "expected a pressure scale rho0 c0^2 (rho0 = " + num(c.fluid.rho0) + ", c0 = " +
                num(c.fluid.c0_factor) + " x 2 u_bulk) of at most " + num(kMaxStateValue) +
                " (single-precision particle state), got " + num(pressure_scale));
  k.require(!c.species.ale || c.scheme == Scheme::modern, "species.ale",
            "expected false with scheme = \"conventional\" (the ALE term du . grad C exists only "
            "in the modern scheme, whose particles move with u + du)");
  k.require(c.fluid.driving == Driving::pressure || c.flow == Flow::wcsph, "fluid.driving",
            "expected \"pressure\" with flow = \"prescribed\" (a prescribed flow solves no "
            "momentum equation for a body force to act on)");
  k.non_negative("modern.delta", c.modern.delta);
  k.range("modern.shift_eps", c.modern.shift_eps, 0.0, false, 1.0, false);
  k.range("modern.shift_max", c.modern.shift_max, 0.0, false, 1.0, false);
}

// The key prefix of species s in messages: "species." for a case of one species, else
// "species[s]." (the [[species]] table).
std::string species_key(const Case& c, int s) {
  return c.more_species.empty() ? std::string("species.") : "species[" + std::to_string(s) + "].";
}

// Species names label files (probes_<name>.csv) and datasets: letters, digits and _.
bool valid_species_name(const std::string& n) {
  if (n.empty() || n.size() > 32) return false;
  for (const char ch : n)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) return false;
  return true;
}

// Every species but the first (check_fluid_species has it): name, D, C values.
void check_more_species(Checker& k, const Case& c) {
  k.require(c.species_count() <= Case::kMaxSpecies, "species",
            "expected at most " + std::to_string(Case::kMaxSpecies) + " [[species]] tables, got " +
                std::to_string(c.species_count()));
  for (int s = 0; s < c.species_count(); ++s) {
    const Case::Species& sp = c.species_at(s);
    const std::string key = species_key(c, s);
    k.require(valid_species_name(sp.name), key + "name",
              "expected a name of 1 to 32 letters, digits and _ (it names output files), got \"" +
                  sp.name.substr(0, 40) + "\"");
    for (int o = 0; o < s; ++o)
      k.require(c.species_at(o).name != sp.name, key + "name",
                "expected a name no other species has, got \"" + sp.name + "\" twice");
    if (s == 0) continue;
    k.non_negative(key + "D", sp.D);
    k.range(key + "c_in", sp.c_in, 0.0, false, kMaxStateValue, false);
    k.range(key + "c_init", sp.c_init, 0.0, false, kMaxStateValue, false);
  }
  k.require(c.more_species.empty() || !c.species.ale, "species.ale",
            "expected false with several species (the ALE term is written for one), got true");
  k.require(c.more_species.empty() || !c.time.warm_start, "time.warm_start",
            "expected false with several species (the warm start hands over the field of one), "
            "got true");
}

// The inlet feed in time of species s (species/inlet_feed.hpp).
void check_feed(Checker& k, const Case& c, int s) {
  const auto& f = c.species_at(s).feed;
  if (f.shape == FeedShape::constant) return;
  const std::string fk = species_key(c, s) + "feed.";
  k.range(fk + "t0", f.t0, 0.0, false, kMaxStateValue, false);
  k.range(fk + "base", f.base, 0.0, false, kMaxStateValue, false);
  if (f.shape == FeedShape::pulse) k.positive(fk + "width", f.width);
  if (f.shape == FeedShape::table) {
    std::string few = "expected at least two [t, C] points with " + fk + "shape = ";
    few.append("\"table\", got ").append(std::to_string(f.table.size()));
    k.require(f.table.size() >= 2, fk + "table", few);
    for (std::size_t i = 0; i < f.table.size(); ++i) {
      std::string key = fk + "table[";
      key.append(std::to_string(i)).append("]");
      const std::string t_key = key + "[0]", c_key = key + "[1]";
      k.range(t_key, f.table[i][0], 0.0, false, kMaxStateValue, false);
      k.range(c_key, f.table[i][1], 0.0, false, kMaxStateValue, false);
      if (i == 0) continue;
      std::string order = "expected increasing times, got ";
      order.append(num(f.table[i][0])).append(" after ").append(num(f.table[i - 1][0]));
      k.require(f.table[i][0] > f.table[i - 1][0], t_key, order);
    }
  }
  // A pulse or a table has no steady state to stop at (before the pulse the field is as
  // steady as it will ever be), and the warm start's steady field is that of a constant feed.
  std::string with = "expected false with " + fk + "shape = \"";
  with.append(to_string(f.shape)).append("\" ");
  const bool transient = f.shape == FeedShape::pulse || f.shape == FeedShape::table;
  k.require(!transient || !c.time.stop_when_steady, "time.stop_when_steady",
            with + "(a run with this feed has no steady state to stop at), got true");
  k.require(!c.time.warm_start, "time.warm_start",
            with + "(the warm start is the steady state of a constant feed), got true");
}

// The [[reaction]] tables (species/reaction_kinetics.hpp).
void check_reactions(Checker& k, const Case& c) {
  for (std::size_t i = 0; i < c.reactions.size(); ++i) {
    const Reaction& r = c.reactions[i];
    std::string key = "reaction[";
    key.append(std::to_string(i)).append("].");
    k.range(key + "k", r.k, 0.0, false, kMaxStateValue, false);
    const bool two = r.law == RateLaw::bimolecular;
    k.require(r.reactants.size() == (two ? 2u : 1u), key + "reactants",
              std::string("expected ") + (two ? "two species (A + B -> products)" : "one species") +
                  " with law = \"" + to_string(r.law) + "\", got " +
                  std::to_string(r.reactants.size()));
    if (two && r.reactants.size() == 2)
      k.require(r.reactants[0] != r.reactants[1], key + "reactants",
                "expected two different species (for 2 A -> products use law = \"nth_order\" "
                "with order = 2)");
    for (std::size_t j = 0; j < r.products.size(); ++j) {
      const int p = r.products[j];
      bool clash = false;
      for (const int q : r.reactants) clash = clash || q == p;
      for (std::size_t o = 0; o < j; ++o) clash = clash || r.products[o] == p;
      k.require(!clash, key + "products[" + std::to_string(j) + "]",
                "expected a species that is neither a reactant nor listed twice, got \"" +
                    c.species_at(p).name + "\"");
    }
    // Orders of real rate laws lie in [0, 3]; 5 leaves room and keeps C^n finite in double.
    if (r.law == RateLaw::nth_order) k.range(key + "order", r.order, 0.0, false, 5.0, false);
    if (r.law == RateLaw::michaelis_menten)
      k.range(key + "km", r.km, 0.0, false, kMaxStateValue, false);
    for (std::size_t z = 0; z < r.zones.size(); ++z) {
      const Reaction::Zone& zone = r.zones[z];
      std::string zk = key + "zones[";
      zk.append(std::to_string(z)).append("]");
      std::string box = "expected x0 < x1 and y0 < y1, got [";
      box.append(num(zone.x0)).append(", ").append(num(zone.x1)).append(", ");
      box.append(num(zone.y0)).append(", ").append(num(zone.y1)).append("]");
      k.require(std::isfinite(zone.x0) && std::isfinite(zone.x1) && std::isfinite(zone.y0) &&
                    std::isfinite(zone.y1) && zone.x0 < zone.x1 && zone.y0 < zone.y1,
                zk, box);
      k.range(zk + "[4]", zone.factor, 0.0, false, kMaxStateValue, false);
    }
  }
}

void check_time_output(Checker& k, const Case& c) {
  const auto& t = c.time;
  k.positive("time.t_end", t.t_end);
  k.require(t.max_steps >= 0, "time.max_steps",
            "expected an integer >= 0 (0 = no limit), got " + std::to_string(t.max_steps));
  k.range("time.cfl", t.cfl, 0.0, true, 1.0, false);
  k.range("time.viscous_number", t.viscous_number, 0.0, true, 0.25, false);
  k.range("time.diffusion_number", t.diffusion_number, 0.0, true, 0.25, false);
  k.non_negative("time.dt", t.dt);
  k.range("time.dt_factor", t.dt_factor, 0.0, false, 100.0, false);
  k.require(!(t.dt > 0.0 && t.dt_factor > 0.0), "time.dt_factor",
            "expected 0 when time.dt is set (both fix the step), got " + num(t.dt_factor));
  k.positive("time.check_interval", t.check_interval);
  k.positive("time.steady_tol", t.steady_tol);
  k.non_negative("time.steady_window", t.steady_window);
  k.non_negative("time.steady_sweep_tol", t.steady_sweep_tol);
  k.non_negative("output.checkpoint_minutes", c.output.checkpoint_minutes);
  k.non_negative("output.outlet_interval", c.output.outlet_interval);
  if (k.problem) return;
  k.range("time.average_window", t.average_window, 0.0, false, t.t_end, true);
  for (std::size_t i = 0; i < c.output.field_times.size(); ++i) {
    const double ft = c.output.field_times[i];
    const std::string key = "output.field_times[" + std::to_string(i) + "]";
    k.range(key, ft, 0.0, true, t.t_end, false);
    if (i == 0) continue;  // (the message below reads the previous time: not for the first)
    const double before = c.output.field_times[i - 1];
    k.require(ft > before, key,
              "expected increasing times, got " + num(ft) + " after " + num(before));
  }
}

}  // namespace

std::optional<Problem> find_species_problem(const Case& c) {
  Checker k;
  check_more_species(k, c);
  return k.problem;
}

std::optional<Problem> find_problem(const Case& c) {
  Checker k;
  k.require(valid_name(c.name), "name",
            "expected a name of 1 to 200 letters, digits and _ - . + (it names the output "
            "directory runs/<name>), got \"" +
                (c.name.size() > 60 ? c.name.substr(0, 60) + "...\" (" +
                                          std::to_string(c.name.size()) + " characters)"
                                    : c.name + "\""));
  check_geometry(k, c);
  check_fluid_species(k, c);
  check_more_species(k, c);
  for (int s = 0; s < c.species_count(); ++s) check_feed(k, c, s);
  check_reactions(k, c);
  check_time_output(k, c);
  return k.problem;
}

}  // namespace case_detail

void validate_case(const Case& c) {
  if (const auto p = case_detail::find_problem(c))
    throw CaseError(c.source.empty() ? std::string("<case>") : c.source.string(), p->key,
                    p->expected);
}

const char* to_string(Scheme s) {
  return s == Scheme::modern ? "modern" : "conventional";
}
const char* to_string(FeedShape f) {
  switch (f) {
    case FeedShape::constant:
      return "constant";
    case FeedShape::step:
      return "step";
    case FeedShape::pulse:
      return "pulse";
    case FeedShape::table:
      return "table";
  }
  return "?";
}
const char* to_string(RateLaw r) {
  switch (r) {
    case RateLaw::first_order:
      return "first_order";
    case RateLaw::nth_order:
      return "nth_order";
    case RateLaw::michaelis_menten:
      return "michaelis_menten";
    case RateLaw::bimolecular:
      return "bimolecular";
  }
  return "?";
}
const char* to_string(Flow f) {
  return f == Flow::wcsph ? "wcsph" : "prescribed";
}

}  // namespace adrsph
