// Depth and stencil test on one pixel.
#include <gtest/gtest.h>

#include <bit>

#include "rhi_reference/depth_stencil.h"

namespace rhi::reference {
namespace {

constexpr DXGI_FORMAT kD32 = DXGI_FORMAT_D32_FLOAT;
constexpr DXGI_FORMAT kD24 = DXGI_FORMAT_D24_UNORM_S8_UINT;

uint32_t Bits(float z) { return std::bit_cast<uint32_t>(z); }

DEPTH_STENCIL_DESC DepthOnly(COMPARISON_FUNC func) {
  DEPTH_STENCIL_DESC desc;
  desc.DepthFunc = func;
  return desc;
}

// Stencil on, depth off, front face ops: fail ZERO, depth-fail INVERT, pass `passOp`.
DEPTH_STENCIL_DESC StencilOnly(COMPARISON_FUNC func, STENCIL_OP passOp) {
  DEPTH_STENCIL_DESC desc;
  desc.DepthEnable = FALSE;
  desc.StencilEnable = TRUE;
  desc.FrontFace = {STENCIL_OP_ZERO, STENCIL_OP_INVERT, passOp, func};
  desc.BackFace = desc.FrontFace;
  return desc;
}

TEST(DepthStencil, EightDepthFunctions) {
  // Stored 0.5. Fragment 0.25 (nearer) and 0.5 (equal), D32: fragment FUNC stored.
  struct Case {
    COMPARISON_FUNC func;
    bool nearerPasses;
    bool equalPasses;
  };
  const Case cases[] = {
      {COMPARISON_NEVER, false, false},        {COMPARISON_LESS, true, false},
      {COMPARISON_EQUAL, false, true},         {COMPARISON_LESS_EQUAL, true, true},
      {COMPARISON_GREATER, false, false},      {COMPARISON_NOT_EQUAL, true, false},
      {COMPARISON_GREATER_EQUAL, false, true}, {COMPARISON_ALWAYS, true, true},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << "func " << c.func);
    EXPECT_EQ(DepthStencilResult(DepthOnly(c.func), 0, true, 0.25f, Bits(0.5f), 0, kD32).passed, c.nearerPasses);
    EXPECT_EQ(DepthStencilResult(DepthOnly(c.func), 0, true, 0.5f, Bits(0.5f), 0, kD32).passed, c.equalPasses);
  }
  // A farther fragment 0.75 passes GREATER only among the strict tests.
  EXPECT_TRUE(DepthStencilResult(DepthOnly(COMPARISON_GREATER), 0, true, 0.75f, Bits(0.5f), 0, kD32).passed);
  EXPECT_FALSE(DepthStencilResult(DepthOnly(COMPARISON_LESS), 0, true, 0.75f, Bits(0.5f), 0, kD32).passed);
}

TEST(DepthStencil, DepthWriteMask) {
  // LESS, 0.25 against 0.5: passes; DEPTH_WRITE_MASK_ALL writes 0.25, ZERO keeps 0.5.
  DEPTH_STENCIL_DESC desc = DepthOnly(COMPARISON_LESS);
  EXPECT_EQ(DepthStencilResult(desc, 0, true, 0.25f, Bits(0.5f), 0, kD32).depth, Bits(0.25f));
  desc.DepthWriteMask = DEPTH_WRITE_MASK_ZERO;
  const DepthStencilOutcome readOnly = DepthStencilResult(desc, 0, true, 0.25f, Bits(0.5f), 0, kD32);
  EXPECT_TRUE(readOnly.passed);
  EXPECT_EQ(readOnly.depth, Bits(0.5f));
  // A failing fragment writes nothing: 0.75 LESS 0.5 fails, depth stays 0.5.
  EXPECT_EQ(DepthStencilResult(DepthOnly(COMPARISON_LESS), 0, true, 0.75f, Bits(0.5f), 0, kD32).depth, Bits(0.5f));
}

TEST(DepthStencil, DepthEnableFalsePassesAndWritesNothing) {
  // FS 17.9: even with NEVER and write mask ALL.
  DEPTH_STENCIL_DESC desc = DepthOnly(COMPARISON_NEVER);
  desc.DepthEnable = FALSE;
  const DepthStencilOutcome out = DepthStencilResult(desc, 0, true, 0.25f, Bits(0.5f), 0, kD32);
  EXPECT_TRUE(out.passed);
  EXPECT_EQ(out.depth, Bits(0.5f));
}

TEST(DepthStencil, D24Quantisation) {
  // FS 17.11: z*(2^24-1) + 0.5, truncated. 2^24-1 = 16777215.
  // 0.25 -> 4194303.75 + 0.5 = 4194304.25 -> 4194304 (truncation alone would give 4194303).
  EXPECT_EQ(DepthToStored(kD24, 0.25f), 4194304u);
  // 0.5 -> 8388607.5 + 0.5 -> 8388608; 1 -> 16777215; 0 -> 0; 1.5 clamps to 1.
  EXPECT_EQ(DepthToStored(kD24, 0.5f), 8388608u);
  EXPECT_EQ(DepthToStored(kD24, 1.0f), 16777215u);
  EXPECT_EQ(DepthToStored(kD24, 0.0f), 0u);
  EXPECT_EQ(DepthToStored(kD24, 1.5f), 16777215u);
  // 1/3 (float 0.33333334) -> 5592405.17 + 0.5 -> 5592405 = 0x555555.
  EXPECT_EQ(DepthToStored(kD24, 1.0f / 3.0f), 0x555555u);
  // D32 keeps the float bits.
  EXPECT_EQ(DepthToStored(kD32, 0.1f), Bits(0.1f));
  EXPECT_FLOAT_EQ(StoredToDepth(kD24, 8388608u), 8388608.0f / 16777215.0f);
}

TEST(DepthStencil, D24ComparesAfterQuantisation) {
  // 0.1f = 0.100000001 -> 1677721.525 + 0.5 -> 1677722. Two float ULPs above it,
  // 0.10000001639 -> 1677721.775 + 0.5 -> 1677722 as well: EQUAL passes on D24
  // while on D32 the two differ.
  const float above = std::bit_cast<float>(Bits(0.1f) + 2);
  EXPECT_EQ(DepthToStored(kD24, 0.1f), 1677722u);
  EXPECT_TRUE(DepthStencilResult(DepthOnly(COMPARISON_EQUAL), 0, true, above, 1677722u, 0, kD24).passed);
  EXPECT_FALSE(DepthStencilResult(DepthOnly(COMPARISON_EQUAL), 0, true, above, Bits(0.1f), 0, kD32).passed);
  // A passing D24 write stores the code: LESS 0.25 against 0.5's code -> 4194304.
  EXPECT_EQ(DepthStencilResult(DepthOnly(COMPARISON_LESS), 0, true, 0.25f, 8388608u, 0, kD24).depth, 4194304u);
}

TEST(DepthStencil, EightStencilOps) {
  // stored 5, ref 0x80.
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_KEEP, 5, 0x80), 5);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_ZERO, 5, 0x80), 0);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_REPLACE, 5, 0x80), 0x80);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_INCR_SAT, 5, 0x80), 6);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_DECR_SAT, 5, 0x80), 4);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_INVERT, 5, 0x80), 0xFA);  // ~0x05
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_INCR, 5, 0x80), 6);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_DECR, 5, 0x80), 4);
}

TEST(DepthStencil, SaturateClampsAndWrapWraps) {
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_INCR_SAT, 255, 0), 255);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_INCR, 255, 0), 0);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_DECR_SAT, 0, 0), 0);
  EXPECT_EQ(ApplyStencilOp(STENCIL_OP_DECR, 0, 0), 255);
}

TEST(DepthStencil, StencilOpsThroughTheWholeTest) {
  // ALWAYS passes, pass op REPLACE with ref 0x80: 5 -> 0x80. Stored depth untouched (depth off).
  const DepthStencilOutcome replaced =
      DepthStencilResult(StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_REPLACE), 0x80, true, 0.3f, 7u, 5, kD24);
  EXPECT_TRUE(replaced.passed);
  EXPECT_EQ(replaced.stencil, 0x80);
  EXPECT_EQ(replaced.depth, 7u);
  // NEVER fails: the fail op ZERO runs, 5 -> 0, and the pixel is rejected.
  const DepthStencilOutcome failed =
      DepthStencilResult(StencilOnly(COMPARISON_NEVER, STENCIL_OP_REPLACE), 0x80, true, 0.3f, 7u, 5, kD24);
  EXPECT_FALSE(failed.passed);
  EXPECT_EQ(failed.stencil, 0);
  // INCR wraps 255 -> 0 through the whole test, INCR_SAT stays 255.
  EXPECT_EQ(DepthStencilResult(StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_INCR), 0, true, 0.3f, 0, 255, kD24).stencil, 0);
  EXPECT_EQ(
      DepthStencilResult(StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_INCR_SAT), 0, true, 0.3f, 0, 255, kD24).stencil,
      255);
}

TEST(DepthStencil, StencilDepthFailOp) {
  // Depth on (LESS) and stencil ALWAYS: fragment 0.75 behind stored 0.5 fails depth,
  // so StencilDepthFailOp (INVERT) runs: 5 -> 0xFA; nothing passes, depth unchanged.
  DEPTH_STENCIL_DESC desc = StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_REPLACE);
  desc.DepthEnable = TRUE;
  desc.DepthFunc = COMPARISON_LESS;
  const uint32_t half = DepthToStored(kD24, 0.5f);
  const DepthStencilOutcome out = DepthStencilResult(desc, 0x80, true, 0.75f, half, 5, kD24);
  EXPECT_FALSE(out.depthPassed);
  EXPECT_TRUE(out.stencilPassed);
  EXPECT_EQ(out.stencil, 0xFA);
  EXPECT_EQ(out.depth, half);
  // Nearer (0.25): both pass, REPLACE -> 0x80, depth written 4194304.
  const DepthStencilOutcome near = DepthStencilResult(desc, 0x80, true, 0.25f, half, 5, kD24);
  EXPECT_TRUE(near.passed);
  EXPECT_EQ(near.stencil, 0x80);
  EXPECT_EQ(near.depth, 4194304u);
}

TEST(DepthStencil, StencilFailBlocksTheDepthWrite) {
  // Depth LESS would pass (0.25 < 0.5), stencil NEVER fails: depth is not written.
  DEPTH_STENCIL_DESC desc = StencilOnly(COMPARISON_NEVER, STENCIL_OP_KEEP);
  desc.DepthEnable = TRUE;
  const uint32_t half = DepthToStored(kD24, 0.5f);
  const DepthStencilOutcome out = DepthStencilResult(desc, 0, true, 0.25f, half, 5, kD24);
  EXPECT_TRUE(out.depthPassed);
  EXPECT_FALSE(out.passed);
  EXPECT_EQ(out.depth, half);
}

TEST(DepthStencil, ReferenceIsOnTheLeft) {
  // (ref & mask) LESS (stored & mask): ref 1 < stored 2 passes, ref 3 < 2 fails.
  EXPECT_TRUE(DepthStencilResult(StencilOnly(COMPARISON_LESS, STENCIL_OP_KEEP), 1, true, 0, 0, 2, kD24).passed);
  EXPECT_FALSE(DepthStencilResult(StencilOnly(COMPARISON_LESS, STENCIL_OP_KEEP), 3, true, 0, 0, 2, kD24).passed);
}

TEST(DepthStencil, ReadMaskAppliesToReferenceAndStoredValue) {
  // ref 0x13, stored 0x23, mask 0x0F: 0x3 EQUAL 0x3 passes; with mask 0xFF 0x13 != 0x23 fails.
  DEPTH_STENCIL_DESC desc = StencilOnly(COMPARISON_EQUAL, STENCIL_OP_KEEP);
  EXPECT_FALSE(DepthStencilResult(desc, 0x13, true, 0, 0, 0x23, kD24).passed);
  desc.StencilReadMask = 0x0F;
  EXPECT_TRUE(DepthStencilResult(desc, 0x13, true, 0, 0, 0x23, kD24).passed);
  // Only the low 8 bits of the reference count: 0x113 behaves as 0x13.
  EXPECT_TRUE(DepthStencilResult(desc, 0x113, true, 0, 0, 0x23, kD24).passed);
}

TEST(DepthStencil, WriteMask) {
  // REPLACE ref 0x0F onto 0xF0 through write mask 0x3C:
  //   (0xF0 & ~0x3C) | (0x0F & 0x3C) = 0xC0 | 0x0C = 0xCC.
  DEPTH_STENCIL_DESC desc = StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_REPLACE);
  desc.StencilWriteMask = 0x3C;
  EXPECT_EQ(DepthStencilResult(desc, 0x0F, true, 0, 0, 0xF0, kD24).stencil, 0xCC);
}

TEST(DepthStencil, FrontAndBackFacesUseTheirOwnOps) {
  // Front pass op INCR, back pass op DECR, stored 5: front 6, back 4.
  DEPTH_STENCIL_DESC desc = StencilOnly(COMPARISON_ALWAYS, STENCIL_OP_INCR);
  desc.BackFace.StencilPassOp = STENCIL_OP_DECR;
  EXPECT_EQ(DepthStencilResult(desc, 0, true, 0, 0, 5, kD24).stencil, 6);
  EXPECT_EQ(DepthStencilResult(desc, 0, false, 0, 0, 5, kD24).stencil, 4);
  // And their own functions: back face NEVER fails while the front passes.
  desc.BackFace.StencilFunc = COMPARISON_NEVER;
  EXPECT_TRUE(DepthStencilResult(desc, 0, true, 0, 0, 5, kD24).passed);
  EXPECT_FALSE(DepthStencilResult(desc, 0, false, 0, 0, 5, kD24).passed);
}

TEST(DepthStencil, NoStencilWithoutStencilBits) {
  // D32_FLOAT has no stencil (FS 17.12): the stencil test passes and nothing is written.
  const DepthStencilOutcome out =
      DepthStencilResult(StencilOnly(COMPARISON_NEVER, STENCIL_OP_ZERO), 0, true, 0, Bits(0.5f), 9, kD32);
  EXPECT_TRUE(out.passed);
  EXPECT_EQ(out.stencil, 9);
  // StencilEnable FALSE on D24: same.
  DEPTH_STENCIL_DESC off = StencilOnly(COMPARISON_NEVER, STENCIL_OP_ZERO);
  off.StencilEnable = FALSE;
  EXPECT_EQ(DepthStencilResult(off, 0, true, 0, 0, 9, kD24).stencil, 9);
}

}  // namespace
}  // namespace rhi::reference
