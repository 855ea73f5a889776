// Small channel cases for the SPH tests: coarse, short, fast.
#pragma once

#include "adrsph/case.hpp"

namespace adrsph::testing {

inline Case short_channel(Scheme scheme, Flow flow, double length = 20.0) {
  Case c;
  c.name = "test_channel";
  c.scheme = scheme;
  c.flow = flow;
  c.geometry.length = length;
  c.particles.dx = 0.5;
  c.time.t_end = 1.0;
  c.species.D = 10.0;
  return c;
}

}  // namespace adrsph::testing
