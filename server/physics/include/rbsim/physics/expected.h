#pragma once
// A value or an error message, for the expected failures of load-time code
// (bad mesh file, bad config) and of changes asked of a world. The one
// exception that crosses the physics API is misuse: World::body with an id
// that names no body of the world throws std::invalid_argument.
// (std::expected is C++23; this is the part of it we need.)

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace rbsim {

struct Error {
  std::string message;
};

template <class T>
class Expected {
 public:
  Expected(T value) : m_content(std::move(value)) {}          // NOLINT: implicit by design
  Expected(Error error) : m_content(std::move(error)) {}      // NOLINT: implicit by design

  bool ok() const { return std::holds_alternative<T>(m_content); }
  explicit operator bool() const { return ok(); }

  const T& value() const& {
    assert(ok());
    return std::get<T>(m_content);
  }
  T& value() & {
    assert(ok());
    return std::get<T>(m_content);
  }
  T&& value() && {
    assert(ok());
    return std::get<T>(std::move(m_content));
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  const Error& error() const {
    assert(!ok());
    return std::get<Error>(m_content);
  }

 private:
  std::variant<T, Error> m_content;
};

}  // namespace rbsim
