// ValidateSoDeclaration and SoBufferStrides: see stream_output.h.
#include <array>
#include <cctype>
#include <map>
#include <optional>
#include <tuple>

#include "spirv/stream_output.h"

namespace rhi::spirv {
namespace {

constexpr char kComponentNames[] = "xyzw";

std::string EntryPrefix(UINT i) { return "SO declaration entry " + std::to_string(i) + ": "; }

// D3D semantics are case-insensitive: compare and print them upper-cased.
std::string UpperName(const char* name) {
  std::string out(name ? name : "");
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string SemanticOf(const SO_DECLARATION_ENTRY& e) { return UpperName(e.SemanticName) + std::to_string(e.SemanticIndex); }

// Declaration-wide limits that do not depend on the entries' contents.
std::string CheckCounts(const SO_DECLARATION_ENTRY* entries, UINT numEntries, const UINT* strides, UINT numStrides,
                        UINT rasterizedStream, const Reflection& shader) {
  if (numEntries > kSoMaxEntries)
    return "SO declaration: NumEntries (" + std::to_string(numEntries) + ") exceeds " +
           std::to_string(kSoMaxEntries) + " (D3D11_SO_STREAM_COUNT * D3D11_SO_OUTPUT_COMPONENT_COUNT)";
  if (numEntries > 0 && !entries) return "SO declaration: pSODeclaration is NULL but NumEntries is " + std::to_string(numEntries);
  if (numStrides > SO_BUFFER_SLOT_COUNT)
    return "SO declaration: NumStrides (" + std::to_string(numStrides) + ") exceeds 4 (D3D11_SO_BUFFER_SLOT_COUNT)";
  if (numStrides > 0 && !strides) return "SO declaration: pBufferStrides is NULL but NumStrides is " + std::to_string(numStrides);
  if (rasterizedStream != SO_NO_RASTERIZED_STREAM && rasterizedStream >= SO_STREAM_COUNT)
    return "SO declaration: RasterizedStream (" + std::to_string(rasterizedStream) +
           ") must be less than 4 (D3D11_SO_STREAM_COUNT) or D3D11_SO_NO_RASTERIZED_STREAM";
  if (shader.stage != Stage::Vertex && shader.stage != Stage::Domain && shader.stage != Stage::Geometry)
    return std::string("SO declaration: stream output needs a VS, DS or GS, not a ") + StageName(shader.stage);
  return {};
}

std::string CheckGap(UINT i, const SO_DECLARATION_ENTRY& e) {
  if (e.SemanticIndex != 0)
    return EntryPrefix(i) + "a gap (SemanticName NULL) must have SemanticIndex 0, not " + std::to_string(e.SemanticIndex);
  if (e.StartComponent != 0)
    return EntryPrefix(i) + "a gap (SemanticName NULL) must have StartComponent 0, not " +
           std::to_string(e.StartComponent);
  if (e.ComponentCount == 0) return EntryPrefix(i) + "a gap (SemanticName NULL) must have ComponentCount >= 1";
  return {};
}

// Component range and the output it captures.
std::string CheckCapture(UINT i, const SO_DECLARATION_ENTRY& e, const Reflection& shader) {
  if (e.ComponentCount < 1 || e.ComponentCount > 4)
    return EntryPrefix(i) + "ComponentCount (" + std::to_string(e.ComponentCount) + ") must be 1..4";
  if (e.StartComponent > 3)
    return EntryPrefix(i) + "StartComponent (" + std::to_string(e.StartComponent) + ") must be 0..3";
  if (e.StartComponent + e.ComponentCount > 4)
    return EntryPrefix(i) + "StartComponent (" + std::to_string(e.StartComponent) + ") + ComponentCount (" +
           std::to_string(e.ComponentCount) + ") exceeds 4";
  const InterfaceVariable* output = shader.FindOutput(e.SemanticName, e.SemanticIndex, e.Stream);
  if (!output || output->stream != e.Stream)
    return EntryPrefix(i) + "unknown semantic \"" + SemanticOf(e) + "\" (not an output of the " +
           StageName(shader.stage) + (e.Stream ? " in stream " + std::to_string(e.Stream) : std::string()) + ")";
  if (output->arraySize != 0 || output->locationCount != 1 || output->scalarWidth != 32)
    return EntryPrefix(i) + "\"" + SemanticOf(e) +
           "\" is an array, matrix or non-32-bit output, which this backend cannot stream out";
  if (e.StartComponent + e.ComponentCount > output->componentCount)
    return EntryPrefix(i) + "\"" + SemanticOf(e) + "\" has " + std::to_string(output->componentCount) +
           " component(s); StartComponent (" + std::to_string(e.StartComponent) + ") + ComponentCount (" +
           std::to_string(e.ComponentCount) + ") exceeds them";
  return {};
}

// Cross-entry rules: each output component once per stream, one stream per slot.
class Overlaps {
 public:
  std::string Add(UINT i, const SO_DECLARATION_ENTRY& e) {
    if (auto it = slotStream_.find(e.OutputSlot); it != slotStream_.end() && it->second.first != e.Stream)
      return EntryPrefix(i) + "OutputSlot " + std::to_string(e.OutputSlot) + " already holds stream " +
             std::to_string(it->second.first) + " (entry " + std::to_string(it->second.second) + "), not stream " +
             std::to_string(e.Stream) + "; an output slot takes one stream";
    slotStream_.try_emplace(e.OutputSlot, e.Stream, i);
    if (!e.SemanticName) return {};
    auto& owners = captured_[{e.Stream, UpperName(e.SemanticName), e.SemanticIndex}];
    for (UINT c = e.StartComponent; c < UINT(e.StartComponent) + e.ComponentCount; ++c) {
      if (owners[c])
        return EntryPrefix(i) + "component " + kComponentNames[c] + " of \"" + SemanticOf(e) +
               "\" is already captured by entry " + std::to_string(*owners[c]);
      owners[c] = i;
    }
    return {};
  }

 private:
  std::map<UINT, std::pair<UINT, UINT>> slotStream_;  // slot -> (stream, first entry)
  std::map<std::tuple<UINT, std::string, UINT>, std::array<std::optional<UINT>, 4>> captured_;
};

std::string CheckEntries(const SO_DECLARATION_ENTRY* entries, UINT numEntries, const Reflection& shader) {
  Overlaps overlaps;
  for (UINT i = 0; i < numEntries; ++i) {
    const SO_DECLARATION_ENTRY& e = entries[i];
    if (e.Stream >= SO_STREAM_COUNT)
      return EntryPrefix(i) + "Stream (" + std::to_string(e.Stream) + ") must be less than 4 (D3D11_SO_STREAM_COUNT)";
    if (e.Stream > 0 && shader.stage != Stage::Geometry)
      return EntryPrefix(i) + "Stream (" + std::to_string(e.Stream) + ") needs a geometry shader; a " +
             StageName(shader.stage) + " has only stream 0";
    if (e.OutputSlot >= SO_BUFFER_SLOT_COUNT)
      return EntryPrefix(i) + "OutputSlot (" + std::to_string(e.OutputSlot) +
             ") must be less than 4 (D3D11_SO_BUFFER_SLOT_COUNT)";
    std::string error = e.SemanticName ? CheckCapture(i, e, shader) : CheckGap(i, e);
    if (error.empty()) error = overlaps.Add(i, e);
    if (!error.empty()) return error;
  }
  return {};
}

std::string CheckStrides(const SO_DECLARATION_ENTRY* entries, UINT numEntries, const UINT* strides, UINT numStrides) {
  std::array<UINT, SO_BUFFER_SLOT_COUNT> bytes{}, captures{}, used{};
  for (UINT i = 0; i < numEntries; ++i) {
    bytes[entries[i].OutputSlot] += 4u * entries[i].ComponentCount;
    used[entries[i].OutputSlot] = 1;
    if (entries[i].SemanticName) captures[entries[i].OutputSlot] = 1;
  }
  for (UINT slot = 0; slot < SO_BUFFER_SLOT_COUNT; ++slot) {
    const std::string name = "pBufferStrides[" + std::to_string(slot) + "] (";
    if (used[slot] && !captures[slot]) return "SO declaration: output slot " + std::to_string(slot) + " contains only gaps";
    if (numStrides == 0) {
      if (bytes[slot] > kSoBufferMaxStrideInBytes)
        return "SO declaration: output slot " + std::to_string(slot) + " takes " + std::to_string(bytes[slot]) +
               " bytes per vertex, more than 2048 (D3D11_SO_BUFFER_MAX_STRIDE_IN_BYTES)";
      continue;
    }
    if (!used[slot]) continue;  // strides of unused slots are never read
    if (slot >= numStrides)
      return "SO declaration: OutputSlot " + std::to_string(slot) + " is used but NumStrides is " +
             std::to_string(numStrides);
    const UINT stride = strides[slot];
    if (stride % 4 != 0) return "SO declaration: " + name + std::to_string(stride) + ") is not a multiple of 4";
    if (stride > kSoBufferMaxStrideInBytes)
      return "SO declaration: " + name + std::to_string(stride) + ") exceeds 2048 (D3D11_SO_BUFFER_MAX_STRIDE_IN_BYTES)";
    if (stride < bytes[slot])
      return "SO declaration: " + name + std::to_string(stride) + ") is smaller than the " +
             std::to_string(bytes[slot]) + " bytes the declaration writes per vertex to slot " + std::to_string(slot);
  }
  return {};
}

}  // namespace

std::string ValidateSoDeclaration(const SO_DECLARATION_ENTRY* entries, UINT numEntries, const UINT* bufferStrides,
                                  UINT numStrides, UINT rasterizedStream, const Reflection& shader) {
  std::string error = CheckCounts(entries, numEntries, bufferStrides, numStrides, rasterizedStream, shader);
  if (error.empty()) error = CheckEntries(entries, numEntries, shader);
  if (error.empty()) error = CheckStrides(entries, numEntries, bufferStrides, numStrides);
  return error;
}

std::array<UINT, SO_BUFFER_SLOT_COUNT> SoBufferStrides(std::span<const SO_DECLARATION_ENTRY> entries,
                                                       std::span<const UINT> bufferStrides) {
  std::array<UINT, SO_BUFFER_SLOT_COUNT> strides{};
  for (const SO_DECLARATION_ENTRY& e : entries)
    if (e.OutputSlot < SO_BUFFER_SLOT_COUNT) strides[e.OutputSlot] += 4u * e.ComponentCount;
  for (size_t slot = 0; slot < bufferStrides.size() && slot < SO_BUFFER_SLOT_COUNT; ++slot)
    strides[slot] = bufferStrides[slot];
  return strides;
}

}  // namespace rhi::spirv
