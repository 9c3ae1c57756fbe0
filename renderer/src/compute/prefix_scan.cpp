// The GPU prefix scan (renderer/compute/prefix_scan.h; shaders_hlsl/compute/prefix_scan.fx).
#include "renderer/compute/prefix_scan.h"

#include <algorithm>

#include "renderer/compute/viewed_buffer.h"
#include "renderer/effect_files.h"

namespace renderer::compute {
namespace {

constexpr uint32_t kScanThreads = 256;              // threads a scan group has (SCAN_THREADS)
constexpr uint32_t kScanBlock = 2 * kScanThreads;   // elements a scan group handles
constexpr uint32_t kMaxGroupsPerDimension = 65535;  // D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION

uint32_t Blocks(uint32_t n) { return (n + kScanBlock - 1) / kScanBlock; }

}  // namespace

// One level: its groups' sums, and their scan (the next level's output), which
// it adds back.
struct PrefixScan::Level {
  uint32_t length = 0;
  ViewedBuffer sums, scannedSums;
};

PrefixScan::PrefixScan() = default;
PrefixScan::~PrefixScan() = default;

std::unique_ptr<PrefixScan> PrefixScan::Create(rhi::Device* device, uint32_t length, std::string* error) {
  std::unique_ptr<PrefixScan> scan(new PrefixScan());
  if (!scan->Initialize(device, length, error)) return nullptr;
  return scan;
}

bool PrefixScan::Initialize(rhi::Device* device, uint32_t length, std::string* error) {
  length_ = length;
  for (uint32_t n = std::max(length, 1u);; n = Blocks(n)) {
    Level& level = levels_.emplace_back();
    level.length = n;
    if (!level.sums.CreateRaw(device, Blocks(n)) || !level.scannedSums.CreateRaw(device, Blocks(n))) {
      *error = "prefix scan: creating the block sums failed";
      return false;
    }
    passNames_.push_back("ScanBlocks");
    if (Blocks(n) == 1) break;
  }
  for (size_t i = 1; i < levels_.size(); ++i) passNames_.push_back("AddBlockOffsets");
  passNamesWithoutTotal_ = passNames_;
  passNames_.push_back("Total");
  effect_ = LoadEffect(device, "compute/prefix_scan.fx", {{"SCAN_THREADS", std::to_string(kScanThreads)}}, error);
  return effect_ && (scanBlocks_ = FindPass(effect_.Get(), nullptr, "ScanBlocks", error)) &&
         (addBlockOffsets_ = FindPass(effect_.Get(), nullptr, "AddBlockOffsets", error)) &&
         (total_ = FindPass(effect_.Get(), nullptr, "Total", error));
}

void PrefixScan::Run(rhi::DeviceContext* ctx, rhi::UnorderedAccessView* input, rhi::UnorderedAccessView* output,
                     rhi::UnorderedAccessView* total, oit::PassMarks* marks, size_t* pass) {
  ScanLevel(ctx, 0, input, output, marks, pass);
  if (!total) return;
  if (marks) marks->BeginPass((*pass)++);
  Dispatch(ctx, total_, length_, input, output, nullptr, total);
}

// The blocks of `level` scanned with their sums out; with more than one block,
// the sums scanned (the next level) and each block's offset added back. The
// passes run in PassNames' order: every level's ScanBlocks, then the
// AddBlockOffsets back up.
void PrefixScan::ScanLevel(rhi::DeviceContext* ctx, size_t level, rhi::UnorderedAccessView* input,
                           rhi::UnorderedAccessView* output, oit::PassMarks* marks, size_t* pass) {
  Level& l = levels_[level];
  if (marks) marks->BeginPass((*pass)++);
  Dispatch(ctx, scanBlocks_, l.length, input, output, l.sums.uav.Get(), nullptr);
  if (level + 1 == levels_.size()) return;
  ScanLevel(ctx, level + 1, l.sums.uav.Get(), l.scannedSums.uav.Get(), marks, pass);
  if (marks) marks->BeginPass((*pass)++);
  Dispatch(ctx, addBlockOffsets_, l.length, input, output, l.scannedSums.uav.Get(), nullptr);
}

void PrefixScan::Dispatch(rhi::DeviceContext* ctx, fx::EffectPass* pass, uint32_t length,
                          rhi::UnorderedAccessView* input, rhi::UnorderedAccessView* output,
                          rhi::UnorderedAccessView* blockSums, rhi::UnorderedAccessView* total) {
  const uint32_t groups = pass == total_ ? 1 : Blocks(length);
  const uint32_t groupsX = std::min(groups, kMaxGroupsPerDimension);
  effect_->GetVariableByName("ScanLength")->AsScalar()->SetInt(int(length));
  effect_->GetVariableByName("ScanGroupsX")->AsScalar()->SetInt(int(groupsX));
  effect_->GetVariableByName("ScanInput")->AsUnorderedAccessView()->SetUnorderedAccessView(input);
  effect_->GetVariableByName("ScanOutput")->AsUnorderedAccessView()->SetUnorderedAccessView(output);
  effect_->GetVariableByName("ScanBlockSums")->AsUnorderedAccessView()->SetUnorderedAccessView(blockSums);
  effect_->GetVariableByName("ScanTotal")->AsUnorderedAccessView()->SetUnorderedAccessView(total);
  pass->Apply(0, ctx);
  ctx->Dispatch(groupsX, (groups + groupsX - 1) / groupsX, 1);
  rhi::UnorderedAccessView* none[4] = {};
  ctx->CSSetUnorderedAccessViews(0, 4, none, nullptr);  // the next pass may read them as shader resources
}

uint64_t PrefixScan::MemoryBytes() const {
  uint64_t bytes = 0;
  for (const Level& level : levels_) bytes += level.sums.bytes + level.scannedSums.bytes;
  return bytes;
}

}  // namespace renderer::compute
