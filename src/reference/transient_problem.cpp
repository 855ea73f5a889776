// The transient reference problem of a case (docs/reference.md, "Transient mode"): the steady
// reactor, the case's initial C, its [species.feed] at x = 0, its end time and outlet interval.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "adrsph/reference_transient.hpp"
#include "species/feed_integral.hpp"
#include "species/inlet_feed.hpp"

namespace adrsph::reference {

TransientProblem transient_problem_from_case(const Case& c) {
  TransientProblem p;
  p.space = problem_from_case(c);
  p.c_init = c.species.c_init;
  // The field stays within [0, max(c_init, feed)]: the reaction terms' slope bound.
  p.space.c_max = std::max(c.species.c_init, feed_max(c.species));
  const Case::Species species = c.species;
  p.inlet_integral = [species](double a, double b) { return feed_integral(species, a, b); };
  // Just before t = 0 (every feature of a feed starts at t >= 0).
  p.inlet_before_start = inlet_concentration(c.species, -std::numeric_limits<double>::min());
  p.t_end = c.time.t_end;
  p.sample_interval = c.output.outlet_interval;
  return p;
}

double default_transient_dt(const Case& c) {
  double feature = c.output.outlet_interval > 0.0 ? c.output.outlet_interval : c.time.t_end;
  // Every species' feed: a network's reference steps them all together.
  for (int s = 0; s < c.species_count(); ++s) {
    const auto& f = c.species_at(s).feed;
    if (f.shape == FeedShape::pulse) feature = std::min(feature, f.width);
    if (f.shape == FeedShape::table)
      for (std::size_t i = 1; i < f.table.size(); ++i)
        if (f.table[i][0] > f.table[i - 1][0])
          feature = std::min(feature, f.table[i][0] - f.table[i - 1][0]);
  }
  return feature / kTransientStepsPerFeature;
}

}  // namespace adrsph::reference
