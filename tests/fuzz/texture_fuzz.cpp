// libFuzzer target for the texture-file loader's parsing (texture_fuzz_common.h).
#include <cstdio>
#include <cstdlib>

#include "texture_fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > texfuzz::kMaxInputBytes) return -1;
  texfuzz::Outcome o = texfuzz::RunOne(data, size);
  for (const std::string& p : o.problems) std::fprintf(stderr, "texture_fuzz: %s\n", p.c_str());
  if (!o.problems.empty()) std::abort();
  return 0;
}
