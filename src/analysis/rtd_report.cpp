#include "analysis/rtd_report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace adrsph::analysis {
namespace {

using Json = nlohmann::ordered_json;

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "n/a";
  char buf[48];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string g4(double v) {
  return fmt("%.4g", v);
}

std::string percent(double v) {
  return fmt("%+.2f%%", 100.0 * v);
}

Json number(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

std::string feed_line(const Rtd& r, const Case& c) {
  const auto& f = c.species.feed;
  std::string s = "Feed: ";
  if (f.shape == FeedShape::pulse)
    s += "pulse of c_in - base = " + g4(c.species.c_in - f.base) + " mol/m^3 over [" + g4(f.t0) +
         ", " + g4(f.t0 + f.width) + ") s";
  else
    s += "table of " + std::to_string(f.table.size()) + " points";
  s += " on base " + g4(f.base) + " (amount " + g4(r.feed.amount) + " mol/m^3 s, mean " +
       g4(r.feed.mean) + " s, variance " + g4(r.feed.variance) + " s^2).\n";
  return s;
}

Json reference_json(const RtdAgainst& a) {
  return Json{{"samples", a.samples},
              {"t_first", a.t_first},
              {"t_last", a.t_last},
              {"feed", Json{{"amount", number(a.feed.amount)},
                            {"mean", number(a.feed.mean)},
                            {"variance", number(a.feed.variance)}}},
              {"outlet", Json{{"area", number(a.outlet.area)},
                              {"mean", number(a.outlet.mean)},
                              {"variance", number(a.outlet.variance)}}},
              {"mean_residence_time", number(a.mean_residence_time)},
              {"variance", number(a.variance)},
              {"recovery", number(a.recovery)},
              {"mean_over_reference_minus_1", number(a.mean_over_reference_minus_1)},
              {"variance_over_reference_minus_1", number(a.variance_over_reference_minus_1)},
              {"L1", number(a.l1)},
              {"case_differences", a.case_differences}};
}

// The section "Against the transient reference" of rtd.md (docs/rtd.md).
std::string reference_markdown(const Rtd& r, const RtdAgainst& a) {
  std::string md = "\n## Against the transient reference\n\n";
  md += "Reference: " + std::to_string(a.samples) +
        " samples of C_flow_mean, t = " + g4(a.t_first) + " to " + g4(a.t_last) +
        " s, moments feed-corrected like the run's.\n\n";
  md += "| quantity | run | reference | difference |\n|---|---|---|---|\n";
  md += "| mean residence time t_m [s] | " + g4(r.mean_residence_time) + " | " +
        g4(a.mean_residence_time) + " | " + percent(a.mean_over_reference_minus_1) + " |\n";
  md += "| variance s^2 [s^2] | " + g4(r.variance) + " | " + g4(a.variance) + " | " +
        percent(a.variance_over_reference_minus_1) + " |\n";
  md += "| recovery | " + fmt("%.4f", r.recovery) + " | " + fmt("%.4f", a.recovery) + " | " +
        percent(r.recovery - a.recovery) + " (absolute) |\n\n";
  md += "Shape: L1 = int |E_run - E_ref| dt = " + fmt("%.3g", a.l1) +
        " on the run's samples (the reference interpolated linearly in t); 0: the same shape, "
        "2: no overlap.\n";
  for (const std::string& d : a.case_differences)
    md += "**Warning:** the reference was solved for another case: " + d + ".\n";
  return md;
}

}  // namespace

std::vector<std::string> rtd_warnings(const Rtd& r, const Case& c) {
  std::vector<std::string> w;
  if (r.truncated)
    w.push_back("the outlet response has not died out: the last sample is " + fmt("%.3g", r.tail) +
                " of the peak (above " + fmt("%g", Rtd::kTruncatedTail) +
                "), so the moments miss the tail and the mean and variance are too small; run "
                "longer (time.t_end)");
  if (!c.reactions.empty())
    w.push_back(
        "the case has [[reaction]] tables: the tracer reacts, so the outlet does not "
        "see E(t) and the moments are biased; a residence-time measurement has none");
  if (c.species.k > 0.0)
    w.push_back("species.k = " + g4(c.species.k) +
                " 1/s: the tracer reacts, so the outlet sees E(t) exp(-k t), not E(t) (recovery "
                "= 1 - conversion) and the moments are biased early; a residence-time "
                "measurement sets species.k = 0");
  if (c.species.c_init != c.species.feed.base)
    w.push_back("species.c_init = " + g4(c.species.c_init) +
                " differs from species.feed.base = " + g4(c.species.feed.base) +
                ": the channel's initial contents leave through the outlet and count as tracer; "
                "a residence-time measurement sets species.c_init = species.feed.base");
  if (!r.has_model) w.push_back("species.D = 0: no Taylor-Aris model (K needs D > 0)");
  return w;
}

std::string rtd_csv(const Rtd& r, const RtdAgainst* against) {
  std::string text = "t_s,C_out,E_per_s,C_model,C_model_closed,C_reference\n";
  char buf[96];
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.10g,%.10g,%.10g,", r.t[i], r.c_out[i], r.e_out[i]);
    text += buf;
    // Empty where there is no model (species.D = 0).
    auto cell = [&](double v) {
      if (!std::isfinite(v)) return;
      std::snprintf(buf, sizeof buf, "%.10g", v);
      text += buf;
    };
    cell(r.c_model[i]);
    text += ',';
    cell(r.c_closed[i]);
    text += ',';
    if (against) cell(against->c_ref[i]);
    text += '\n';
  }
  return text;
}

std::string rtd_json(const Rtd& r, const Case& c, const RtdAgainst* against) {
  const auto& f = c.species.feed;
  const bool pulse = f.shape == FeedShape::pulse;
  Json j;
  j["case"] = c.name;
  j["Pe"] = number(c.peclet());
  j["D"] = c.species.D;
  j["k"] = c.species.k;
  j["R"] = c.geometry.half_width;
  j["L"] = c.geometry.length;
  j["u_bulk"] = c.fluid.u_bulk;
  j["u_mean"] = r.mean_velocity;
  j["feed"] = Json{{"shape", to_string(f.shape)},
                   {"t0", pulse ? Json(f.t0) : Json(nullptr)},
                   {"width", pulse ? Json(f.width) : Json(nullptr)},
                   {"base", f.base},
                   {"amount", number(r.feed.amount)},
                   {"mean", number(r.feed.mean)},
                   {"variance", number(r.feed.variance)}};
  j["samples"] = r.t.size();
  j["t_first"] = r.t.front();
  j["t_last"] = r.t.back();
  j["outlet"] = Json{{"area", number(r.outlet.area)},
                     {"mean", number(r.outlet.mean)},
                     {"variance", number(r.outlet.variance)}};
  j["mean_residence_time"] = number(r.mean_residence_time);
  j["space_time"] = number(r.space_time);
  j["mean_over_space_time_minus_1"] = number(r.mean_over_space_time_minus_1());
  j["variance"] = number(r.variance);
  j["recovery"] = number(r.recovery);
  j["tail"] = number(r.tail);
  j["truncated"] = r.truncated;
  j["model"] = Json{{"name", "Taylor-Aris"},
                    {"K", number(r.model.dispersion)},
                    {"Pe_L", number(r.model.peclet_length)},
                    {"mean", number(r.model.residence.mean)},
                    {"variance", number(r.model.residence.variance())},
                    {"applicability", number(r.model.applicability)},
                    {"applies", r.has_model && r.model.applies()},
                    {"outlet_area", number(r.model_area)}};
  j["variance_over_model_minus_1"] = number(r.variance_over_model_minus_1());
  j["L1"] = number(r.l1);
  j["closed_outlet_model"] = Json{{"name", "Taylor-Aris, Dirichlet inlet, no flux at x = L"},
                                  {"mean", number(r.closed_mean)},
                                  {"variance", number(r.closed_variance)},
                                  {"L1", number(r.closed_l1)}};
  j["mean_over_closed_minus_1"] = number(r.mean_over_closed_minus_1());
  j["variance_over_closed_minus_1"] = number(r.variance_over_closed_minus_1());
  j["reference"] = against ? reference_json(*against) : Json(nullptr);
  j["warnings"] = rtd_warnings(r, c);
  return j.dump(2) + "\n";
}

std::string rtd_markdown(const Rtd& r, const Case& c, const RtdAgainst* against) {
  std::string md = "# Residence-time distribution: " + c.name + "\n\n";
  md += feed_line(r, c);
  md += "Outlet: " + std::to_string(r.t.size()) +
        " samples of C_flow_mean, t = " + g4(r.t.front()) + " to " + g4(r.t.back()) + " s.\n";
  md += "Flow: U = " + g4(r.mean_velocity) +
        " mm/s (the mean of u(y), u_max = 2 u_bulk), L = " + g4(c.geometry.length) +
        " mm, R = " + g4(c.geometry.half_width) + " mm, D = " + g4(c.species.D) +
        " mm^2/s (Pe = u_bulk L / D = " + g4(c.peclet()) + "), k = " + g4(c.species.k) +
        " 1/s.\n\n";
  md += "| quantity | run | expected | difference |\n|---|---|---|---|\n";
  md += "| mean residence time t_m [s] | " + g4(r.mean_residence_time) +
        " | V/Q = L/U = " + g4(r.space_time) + " | " + percent(r.mean_over_space_time_minus_1()) +
        " |\n";
  md += "| variance s^2 [s^2] | " + g4(r.variance) +
        " | Taylor-Aris 2 K L / U^3 = " + g4(r.model.residence.variance()) + " | " +
        percent(r.variance_over_model_minus_1()) + " |\n";
  if (r.has_model) {
    md += "| t_m against the dispersion model on the channel's boundary conditions | " +
          g4(r.mean_residence_time) + " | " + g4(r.closed_mean) + " | " +
          percent(r.mean_over_closed_minus_1()) + " |\n";
    md += "| s^2 against the same | " + g4(r.variance) + " | " + g4(r.closed_variance) + " | " +
          percent(r.variance_over_closed_minus_1()) + " |\n";
  }
  md += "| recovery (outlet / feed amount) | " + fmt("%.4f", r.recovery) +
        " | 1 (conserved tracer) | " + percent(r.recovery - 1.0) + " |\n\n";
  if (r.has_model) {
    md += "Taylor-Aris: K = " + g4(r.model.dispersion) +
          " mm^2/s, Pe_L = U L / K = " + g4(r.model.peclet_length) + ".\n";
    const double mixing = c.geometry.half_width * c.geometry.half_width / c.species.D;
    md +=
        "Applicability: tau D / R^2 = " + g4(r.model.applicability) +
        (r.model.applies()
             ? " >= 10: the model applies (transverse mixing time R^2/D = " + g4(mixing) +
                   " s, well below tau).\n"
             : " < 10: the model is only indicative (transverse mixing time R^2/D = " + g4(mixing) +
                   " s is not well below tau = " + g4(r.space_time) + " s).\n");
    md += "Shape: L1 distance of the normalised outlet responses, run against model = " +
          fmt("%.3g", r.l1) + " (semi-infinite medium), " + fmt("%.3g", r.closed_l1) +
          " (channel's boundary conditions); 0: the same shape, 2: no overlap.\n";
    md +=
        "V/Q and 2 K L / U^3 are those of a semi-infinite medium; the channel's inlet is held "
        "at the feed (tracer diffuses back out after the pulse) and its outlet passes no "
        "dispersive flux, which the closed model includes (docs/rtd.md, section 6).\n";
  }
  md += "Tail: the last sample is " + fmt("%.3g", r.tail) + " of the peak.\n";
  const auto warnings = rtd_warnings(r, c);
  if (!warnings.empty()) md += "\n";
  for (const std::string& w : warnings) md += "**Warning:** " + w + ".\n";
  if (against) md += reference_markdown(r, *against);
  return md;
}

}  // namespace adrsph::analysis
