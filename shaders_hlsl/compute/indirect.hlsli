// What a compute shader dispatched with renderer::compute::DispatchArgs
// (renderer/compute/dispatch_args.h) includes: the linear index of its group and
// the item count the dispatch was sized for, both from the GPU-written arguments.
//
// DispatchArgs writes a slot of 4 words at byte IndirectArgsOffset of its buffer:
// groups in x, groups in y, groups in z (1), then the count. A group count over
// D3D11's 65,535 a dimension is split into x and y, so the grid may hold a few
// groups past the last one: IndirectGroupIndex(group) * items per group >=
// IndirectCount() marks them, and they must do nothing.
// DispatchArgs::Bind sets IndirectArgs (the buffer's raw SRV) and IndirectArgsOffset.
#ifndef COMPUTE_INDIRECT_HLSLI
#define COMPUTE_INDIRECT_HLSLI

ByteAddressBuffer IndirectArgs;
cbuffer IndirectParams {
  uint IndirectArgsOffset;  // bytes: the slot this dispatch was sized by
};

// SV_GroupID as the group's index in the dispatch: group.y * groups in x + group.x.
uint IndirectGroupIndex(uint3 group) { return group.y * IndirectArgs.Load(IndirectArgsOffset) + group.x; }

// The count the dispatch was sized for (clamped to DispatchArgs::Write's maxCount).
uint IndirectCount() { return IndirectArgs.Load(IndirectArgsOffset + 12); }

#endif
