// DispatchIndirect arguments from a count on the GPU (renderer/compute/dispatch_args.h):
// one thread reads word CountWord of Count, clamps it to MaxCount and writes a slot
// of compute/indirect.hlsli's layout at byte ArgsOffset of Args: groups in x, y, z
// and the clamped count.
cbuffer DispatchArgsParams {
  uint CountWord;        // which word of Count holds the count
  uint ItemsPerGroup;    // threads (items) a group of the dispatch handles, >= 1
  uint MaxCount;         // counts above it are taken as it
  uint ArgsOffset;       // bytes: the slot's first word in Args
};
RWByteAddressBuffer Count : register(u0);
RWByteAddressBuffer Args : register(u1);

// D3D11_CS_DISPATCH_MAX_THREAD_GROUPS_PER_DIMENSION
static const uint kMaxGroupsPerDimension = 65535;

// ceil(a / b) without overflowing near 2^32.
uint CeilDiv(uint a, uint b) { return a / b + (a % b != 0 ? 1 : 0); }

[numthreads(1, 1, 1)]
void CSWriteArgs() {
  uint count = min(Count.Load(CountWord * 4), MaxCount);
  uint groups = CeilDiv(count, ItemsPerGroup);
  // The fewest rows of at most 65,535 groups, then the fewest groups a row: at
  // most groupsY - 1 groups past the last. (65,535 rows hold any count a buffer
  // of 2^32 bytes can.)
  uint groupsY = max(CeilDiv(groups, kMaxGroupsPerDimension), 1);
  uint groupsX = CeilDiv(groups, groupsY);
  Args.Store4(ArgsOffset, uint4(groupsX, groupsY, 1, count));
}

technique11 DispatchArgs {
  pass Write { SetComputeShader(CompileShader(cs_5_0, CSWriteArgs())); }
}
