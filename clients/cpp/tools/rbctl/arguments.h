#pragma once
// rbctl's command line: a cursor over the arguments with typed readers. Bad
// input throws UsageError, which main() reports with exit code 2.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "rbsim/client/wrench.h"

namespace rbsim::rbctl {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Arguments {
 public:
  explicit Arguments(std::vector<std::string> arguments) : m_arguments(std::move(arguments)) {}

  bool empty() const { return m_next >= m_arguments.size(); }
  const std::string& peek() const { return m_arguments.at(m_next); }
  // The next argument; throws "<option>: missing <what>" at the end.
  std::string next(const std::string& option, const std::string& what);
  double nextNumber(const std::string& option);
  int64_t nextInteger(const std::string& option);
  client::Vec3 nextVec3(const std::string& option);
  // Throws unless every argument was used.
  void expectEnd() const;

 private:
  std::vector<std::string> m_arguments;
  std::size_t m_next = 0;
};

// Whole-string conversions; `what` names the value in the error.
double parseNumber(const std::string& text, const std::string& what);
int64_t parseInteger(const std::string& text, const std::string& what);

}  // namespace rbsim::rbctl
