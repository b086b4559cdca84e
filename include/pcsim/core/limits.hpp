// Bounds of the physical input values (issue 22): every number a scene, a
// design or a pantograph model gives is checked against a finite range, so
// that an implausible magnitude (a tension of 1e300 N, a cut-off of 5e-324 Hz)
// is an input error naming its key instead of a NaN in the solver. The bounds
// are wide and physically motivated (a real line or pantograph is orders of
// magnitude inside them); docs/scene-format.md, docs/design-format.md and
// docs/line-design.md list them with each key.
#pragma once

#include <cmath>
#include <string>

#include "pcsim/core/error.hpp"
#include "pcsim/core/format.hpp"

namespace pcsim {

// A range [min, max] of a value's magnitude in 'unit' (min 0: only the
// sign checks of the reader apply at the lower end).
struct Limit {
  double max;
  const char* unit;
  double min = 0.0;
};

namespace limits {
// Wires and bars.
inline constexpr Limit tension{1e7, "N"};                // contact wires 1e4-4e4 N
inline constexpr Limit axial_stiffness{1e11, "N"};       // EA: steel rods ~1e8 N
inline constexpr Limit bending_stiffness{1e6, "N m^2"};  // EI: contact wires ~200
inline constexpr Limit mass_per_length{1e4, "kg/m"};     // wires ~1 kg/m
inline constexpr Limit thermal_expansion{1e-3, "1/K"};   // copper, bronze 1.7e-5; steel 1.2e-5
inline constexpr Limit wire_diameter{1.0, "m"};          // wires 5-20 mm
inline constexpr Limit drag_coefficient{10.0, ""};       // round wires 1.0-1.2
inline constexpr Limit wind_speed{100.0, "m/s"};         // design gusts ~25-50 m/s
inline constexpr Limit air_density{10.0, "kg/m^3"};      // 1.25 at sea level
inline constexpr Limit drag_area{100.0, "m^2"};          // a pantograph's Cd A ~0.2-1 m^2
inline constexpr Limit stiffness{1e12, "N/m"};           // springs, droppers, contact
inline constexpr Limit mass{1e5, "kg"};                  // clamps, arms, weights, stages
inline constexpr Limit damping{1e8, "N s/m"};            // pantograph stages ~10-100
inline constexpr Limit force{1e6, "N"};                  // pantograph forces ~100 N
// Geometry of a line [m].
inline constexpr Limit span_length{1e4, "m"};           // spans 30-80 m
inline constexpr Limit height{1e3, "m"};                // system and wire heights, sags, staggers
inline constexpr Limit distance{1e7, "m"};              // lengths along a line (ramps, radii)
inline constexpr Limit element_length{1e4, "m", 1e-4};  // 0.1 mm .. (and at most a span)
// Pantograph geometry [m] and rotational properties.
inline constexpr Limit pantograph_length{100.0, "m"};  // DSA-380 bars ~1-2 m
inline constexpr Limit inertia{1e5, "kg m^2"};
inline constexpr Limit rotational_stiffness{1e9, "N m/rad"};
inline constexpr Limit cubic_stiffness{1e18, "N/m^3"};
inline constexpr Limit base_motion{1.0, "m"};       // vehicle roof motion ~1-10 mm
inline constexpr Limit density{1e5, "kg/m^3"};      // steel 7850
inline constexpr Limit youngs_modulus{1e13, "Pa"};  // steel 2.1e11
// Time and frequency.
inline constexpr Limit time_step{1.0, "s", 1e-7};   // runs use 1e-4 .. 1e-3 s
inline constexpr Limit frequency{1e5, "Hz", 1e-3};  // cut-offs and modal bands
inline constexpr Limit time{1e6, "s"};              // durations, time constants
inline constexpr Limit speed_kmh{1000.0, "km/h"};   // trains up to ~600 km/h
inline constexpr Limit gravity{100.0, "m/s^2"};     // 9.81
inline constexpr Limit rayleigh_alpha{1e4, "1/s"};  // lines ~0.01-1 1/s
inline constexpr Limit rayleigh_beta{1.0, "s"};     // lines ~1e-5-1e-3 s
inline constexpr Limit coefficient{1e6, ""};        // aerodynamic coefficients
}  // namespace limits

// "0.0001 .. 1e+07 N" for messages and docs.
inline std::string limit_text(const Limit& limit) {
  std::string unit = *limit.unit ? std::string(" ") + limit.unit : std::string();
  if (limit.min > 0) return format_number(limit.min) + " .. " + format_number(limit.max) + unit;
  return "at most " + format_number(limit.max) + unit;
}

// Why 'value' breaks the limit's bounds on its magnitude ("" if it does not).
inline std::string limit_violation(double value, const Limit& limit) {
  const std::string got = " (got " + format_number(value) + ")";
  const std::string unit = *limit.unit ? std::string(" ") + limit.unit : std::string();
  if (std::abs(value) > limit.max)
    return "must be at most " + format_number(limit.max) + unit + " in magnitude" + got +
           ": not a physical value";
  if (limit.min > 0 && value != 0 && std::abs(value) < limit.min)
    return "must be at least " + format_number(limit.min) + unit + " in magnitude" + got +
           ": not a physical value";
  return "";
}

// Throws InputError(file, key, reason) if 'value' breaks the limit.
inline void require_within(const std::string& file, const std::string& key, double value,
                           const Limit& limit) {
  const std::string why = limit_violation(value, limit);
  if (!why.empty()) throw InputError(file, key, why);
}

}  // namespace pcsim
