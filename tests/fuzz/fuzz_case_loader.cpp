// libFuzzer target for the case loader and the --set parser (docs/robustness.md).
//
// Input: the text of a case file, optionally followed by a line "--set" and one override
// ("key=value") per line. Every input must either load or be refused with a CaseError that
// says something; any other exception, a crash, a leak or undefined behaviour (the target is
// built with AddressSanitizer and UndefinedBehaviorSanitizer) is a finding.
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DADRSPH_FUZZ=ON
//   cmake --build build-fuzz --target adrsph_fuzz_case
//   build-fuzz/adrsph_fuzz_case -max_total_time=60 tests/fuzz/corpus
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "adrsph/case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string marker = "\n--set\n";
  const std::size_t at = input.find(marker);
  const std::string text = input.substr(0, at);
  std::vector<std::string> overrides;
  if (at != std::string::npos) {
    std::size_t line = at + marker.size();
    while (line < input.size()) {
      const std::size_t end = std::min(input.find('\n', line), input.size());
      overrides.push_back(input.substr(line, end - line));
      line = end + 1;
    }
  }
  try {
    const adrsph::Case c = adrsph::load_case_text(text, "fuzz.toml", overrides);
    // A case that loads is valid: its derived numbers are finite.
    if (!(c.h() > 0.0) || !std::isfinite(c.c0())) std::abort();
  } catch (const adrsph::CaseError& e) {
    if (std::string(e.what()).empty()) std::abort();  // a refusal must say why
  }
  return 0;
}
