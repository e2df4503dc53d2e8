#include "arguments.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace rbsim::rbctl {

double parseNumber(const std::string& text, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    throw UsageError(what + ": expected a finite number, got '" + text + "'");
  return value;
}

int64_t parseInteger(const std::string& text, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    throw UsageError(what + ": expected an integer, got '" + text + "'");
  return value;
}

std::string Arguments::next(const std::string& option, const std::string& what) {
  if (empty()) throw UsageError(option + ": missing " + what);
  return m_arguments[m_next++];
}

double Arguments::nextNumber(const std::string& option) {
  return parseNumber(next(option, "a number"), option);
}

int64_t Arguments::nextInteger(const std::string& option) {
  return parseInteger(next(option, "an integer"), option);
}

client::Vec3 Arguments::nextVec3(const std::string& option) {
  client::Vec3 v{};
  for (double& component : v) component = parseNumber(next(option, "three numbers X Y Z"), option);
  return v;
}

void Arguments::expectEnd() const {
  if (!empty()) throw UsageError("unexpected argument '" + m_arguments[m_next] + "'");
}

}  // namespace rbsim::rbctl
