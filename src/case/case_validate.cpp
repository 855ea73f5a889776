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
  void at_least(const std::string& key, long v, long lo) {
    require(v >= lo, key,
            "expected an integer >= " + std::to_string(lo) + ", got " + std::to_string(v));
  }

  static constexpr double kInf = std::numeric_limits<double>::infinity();
};

bool valid_name(const std::string& n) {
  if (n.empty() || n.front() == '.' || n.front() == '-') return false;
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
  k.at_least("particles.wall_layers", c.particles.wall_layers, 3);
  k.at_least("particles.inlet_layers", c.particles.inlet_layers, 4);
  k.at_least("particles.outlet_layers", c.particles.outlet_layers, 3);
  k.range("particles.skin", c.particles.skin, 0.0, false, 1.0, false);
}

void check_fluid_species(Checker& k, const Case& c) {
  k.positive("fluid.rho0", c.fluid.rho0);
  k.positive("fluid.nu", c.fluid.nu);
  k.positive("fluid.u_bulk", c.fluid.u_bulk);
  k.positive("fluid.c0_factor", c.fluid.c0_factor);
  k.range("fluid.gamma", c.fluid.gamma, 1.0, false, Checker::kInf, false);
  k.non_negative("fluid.background_pressure", c.fluid.background_pressure);
  k.non_negative("species.D", c.species.D);
  k.non_negative("species.k", c.species.k);
  k.non_negative("species.c_in", c.species.c_in);
  k.non_negative("species.c_init", c.species.c_init);
  k.require(!c.species.ale || c.scheme == Scheme::modern, "species.ale",
            "expected false with scheme = \"conventional\" (the ALE term du . grad C exists only "
            "in the modern scheme, whose particles move with u + du)");
  k.non_negative("modern.delta", c.modern.delta);
  k.range("modern.shift_eps", c.modern.shift_eps, 0.0, false, 1.0, false);
  k.range("modern.shift_max", c.modern.shift_max, 0.0, false, 1.0, false);
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
  k.positive("time.check_interval", t.check_interval);
  k.positive("time.steady_tol", t.steady_tol);
  k.non_negative("time.steady_window", t.steady_window);
  k.non_negative("time.steady_sweep_tol", t.steady_sweep_tol);
  k.non_negative("output.checkpoint_minutes", c.output.checkpoint_minutes);
  if (k.problem) return;
  k.range("time.average_window", t.average_window, 0.0, false, t.t_end, true);
  for (std::size_t i = 0; i < c.output.field_times.size(); ++i) {
    const double ft = c.output.field_times[i];
    const std::string key = "output.field_times[" + std::to_string(i) + "]";
    k.range(key, ft, 0.0, true, t.t_end, false);
    k.require(
        i == 0 || ft > c.output.field_times[i - 1], key,
        "expected increasing times, got " + num(ft) + " after " + num(c.output.field_times[i - 1]));
  }
}

}  // namespace

std::optional<Problem> find_problem(const Case& c) {
  Checker k;
  k.require(valid_name(c.name), "name",
            "expected a non-empty name of letters, digits and _ - . + (it names the output "
            "directory runs/<name>), got \"" +
                c.name + "\"");
  check_geometry(k, c);
  check_fluid_species(k, c);
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
const char* to_string(Flow f) {
  return f == Flow::wcsph ? "wcsph" : "prescribed";
}

}  // namespace adrsph
