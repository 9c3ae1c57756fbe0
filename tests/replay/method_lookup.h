// The registered method of a name the test knows exists (renderer::oit::FindMethod
// gives null for an unknown one: the test would crash, so it fails first).
#pragma once

#include <gtest/gtest.h>

#include "renderer/oit/method.h"

namespace rhi_test {

inline const renderer::oit::MethodInfo& Method(const char* name) {
  const renderer::oit::MethodInfo* method = renderer::oit::FindMethod(name);
  if (!method) ADD_FAILURE() << "no registered method " << name;
  return method ? *method : *renderer::oit::Methods().front();
}

}  // namespace rhi_test
