#pragma once
// A double as text that reads back as the very same double (17 significant
// digits): for messages that compare values bit for bit and for reports.

#include <cstdio>
#include <string>

namespace rbsim {

inline std::string exactText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace rbsim
