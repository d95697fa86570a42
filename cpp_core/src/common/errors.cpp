#include "tessella/errors.h"

#include <cmath>
#include <sstream>

namespace tessella {

void require_in_range(const char* name, double value, double lo, double hi) {
  if (std::isfinite(value) && value >= lo && value <= hi) return;
  std::ostringstream msg;
  msg << name << " must be in [" << lo << ", " << hi << "], got " << value;
  throw InvalidParameter(msg.str());
}

}  // namespace tessella
