// The SPH variants as types: each says at compile time which pieces of physics it needs,
// so the passes (templates over the scheme) carry no run-time branch on options.
#pragma once

namespace adrsph {

// Conventional WCSPH (paper section 2): summation density, Tait EOS with background
// pressure, particles move with the fluid velocity u.
struct ConventionalScheme {
  static constexpr const char* name = "conventional";
  static constexpr bool summation_density = true;
  static constexpr bool continuity = false;
  static constexpr bool shifting = false;
  static constexpr bool momentum = true;
  static constexpr bool dilatation = true;  // eq. 12's -C div u term (the flow is compressible)
};

// Modern WCSPH with transport velocity: continuity with density diffusion (eq. 8),
// particles move with u + du, du the shifting velocity (eq. 10).
struct ModernScheme {
  static constexpr const char* name = "modern";
  static constexpr bool summation_density = false;
  static constexpr bool continuity = true;
  static constexpr bool shifting = true;
  static constexpr bool momentum = true;
  static constexpr bool dilatation = true;
};

// Prescribed (kinematic) flow: particles move with the analytic velocity, rho = rho0;
// only the species equation is solved. div u = 0 exactly, so the -C div u term is dropped.
struct PrescribedFlow {
  static constexpr const char* name = "prescribed";
  static constexpr bool summation_density = false;
  static constexpr bool continuity = false;
  static constexpr bool shifting = false;
  static constexpr bool momentum = false;
  static constexpr bool dilatation = false;  // div u = 0 exactly
};

}  // namespace adrsph
