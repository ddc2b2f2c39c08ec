// Tests: a setting changed for one scope and put back when it ends, even when a REQUIRE
// throws, so that a failed case leaves no setting behind for the next one (e.g. a shared
// vk::Context's exact_curvature_on_device or sweep_variant).
#pragma once

namespace meshsal_test {

template <class T>
class ScopedValue {
 public:
  ScopedValue(T& target, T value) : target_(target), old_(target) { target_ = value; }
  ~ScopedValue() { target_ = old_; }
  ScopedValue(const ScopedValue&) = delete;
  ScopedValue& operator=(const ScopedValue&) = delete;

 private:
  T& target_;
  T old_;
};

}  // namespace meshsal_test
