// Numbers in messages (input errors, warnings): six significant digits,
// the shortest form (1e+09, 0.15, 2.5).
#pragma once

#include <sstream>
#include <string>

namespace pcsim {

inline std::string format_number(double value) {
  std::ostringstream s;
  s << value;  // default precision: 6 significant digits
  return s.str();
}

}  // namespace pcsim
