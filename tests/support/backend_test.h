// The fixture of every test over backends: a test parameterised by a backend
// (or by anything naming one in `which`: a mode, a backend and a case, ...)
// is skipped, with the reason, where this machine (or RAYCAST_MAX_ISA) cannot
// run that backend. Fixtures of their own derive from it and call its SetUp
// first, returning where IsSkipped().
#pragma once
#include <gtest/gtest.h>

#include "render/backend.h"

namespace raycast_test {

inline raycast::backend backend_of(raycast::backend b) { return b; }
template <class Param>
raycast::backend backend_of(const Param& p) {
  return p.which;
}

template <class Param>
class backend_test : public ::testing::TestWithParam<Param> {
 protected:
  void SetUp() override {
    const raycast::backend b = backend_of(this->GetParam());
    if (auto why = raycast::backend_unavailable(b)) GTEST_SKIP() << to_string(b) << " skipped: " << *why;
  }
};

}  // namespace raycast_test
