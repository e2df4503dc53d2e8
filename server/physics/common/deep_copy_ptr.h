#pragma once
// An owning pointer that copies what it points to when it is copied, so a
// class can hold an incomplete (forward-declared) type by value semantics.
// The copy and destruction are instantiated where T is complete.

#include <memory>
#include <utility>

namespace rbsim {

template <class T>
class DeepCopyPtr {
 public:
  DeepCopyPtr() = default;
  explicit DeepCopyPtr(std::unique_ptr<T> value) : m_value(std::move(value)) {}
  DeepCopyPtr(const DeepCopyPtr& other)
      : m_value(other.m_value ? std::make_unique<T>(*other.m_value) : nullptr) {}
  DeepCopyPtr(DeepCopyPtr&&) noexcept = default;
  DeepCopyPtr& operator=(const DeepCopyPtr& other) {
    if (this != &other) m_value = other.m_value ? std::make_unique<T>(*other.m_value) : nullptr;
    return *this;
  }
  DeepCopyPtr& operator=(DeepCopyPtr&&) noexcept = default;
  ~DeepCopyPtr() = default;

  T* get() const { return m_value.get(); }
  T& operator*() const { return *m_value; }
  T* operator->() const { return m_value.get(); }
  explicit operator bool() const { return static_cast<bool>(m_value); }

 private:
  std::unique_ptr<T> m_value;
};

}  // namespace rbsim
