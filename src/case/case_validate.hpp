// The physical and geometric checks of a Case (internal to src/case).
#pragma once

#include <optional>
#include <string>

#include "adrsph/case.hpp"

namespace adrsph::case_detail {

struct Problem {
  std::string key;       // dotted key at fault
  std::string expected;  // what it should be, with the value found
};

// The first problem found, in the order of cases/README.md; nullopt when the case is valid.
// The rules of the species tables alone (names, count, values): checked before the
// reactions' species names are resolved against them.
std::optional<Problem> find_species_problem(const Case& c);
std::optional<Problem> find_problem(const Case& c);

}  // namespace adrsph::case_detail
