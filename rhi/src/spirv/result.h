// A small std::expected stand-in (GCC 12 / C++20 has none): a value plus an
// error string that is empty on success.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rhi::spirv {

template <class T>
struct Result {
  T value{};
  std::string error;  // empty on success

  bool ok() const { return error.empty(); }
  explicit operator bool() const { return ok(); }
  const T& operator*() const { return value; }
  T& operator*() { return value; }
  const T* operator->() const { return &value; }
  T* operator->() { return &value; }

  static Result Success(T v) { return Result{std::move(v), {}}; }
  static Result Failure(std::string message) { return Result{T{}, message.empty() ? "unknown error" : std::move(message)}; }
};

using Words = std::vector<uint32_t>;
using WordsResult = Result<Words>;

}  // namespace rhi::spirv
