#include "rhi_reference/blend.h"

#include <cmath>
#include <stdexcept>

namespace rhi::reference {
namespace {

constexpr int kAlpha = 3;

// FS 3.1.3: float32 operations flush denorms to a sign-preserved zero, on input
// and on output. The blender follows the float32 rules (FS 17.5).
float FlushDenorm(float x) {
  return std::fpclassify(x) == FP_SUBNORMAL ? std::copysign(0.0f, x) : x;
}

// max then min with the shader semantics (FS 22.10.10/11: a NaN operand loses),
// so a NaN entering a UNORM blend becomes 0, as FS 3.2.3.6 converts NaN.
float Saturate(float x) { return std::fmin(std::fmax(x, 0.0f), 1.0f); }

// FS 17.5: "Values entering Blending Hardware, including the BlendFactor value,
// are always clamped to the range of the RenderTarget before being used", every
// component, present in the format or not. float16 targets may skip the clamp
// ("permitted to not clamp"); the reference blends them unclamped in float32.
Float4 EnterBlender(DXGI_FORMAT format, Float4 value) {
  for (float& channel : value) {
    channel = IsNormalizedFormat(format) ? Saturate(channel) : FlushDenorm(channel);
  }
  return value;
}

struct BlenderInputs {
  Float4 src0;    // SV_Target of this target
  Float4 src1;    // SV_Target1 (dual source)
  Float4 dest;    // the render target, decoded (sRGB decoded to linear, FS 17.4)
  Float4 factor;  // OMSetBlendState's blend factor
  SatReading sat = SatReading::Formula;
};

// SRC_ALPHA_SAT's f before any reading is applied.
float SrcAlphaSat(const BlenderInputs& in) { return std::fmin(in.src0[kAlpha], 1.0f - in.dest[kAlpha]); }

// What the factor is made of, for the tolerance model (FactorSource).
FactorSource SourceOf(BLEND blend, int channel, const BlenderInputs& in) {
  FactorSource s{blend, 0.0f, 0.0f};
  switch (blend) {
    case BLEND_ZERO:
    case BLEND_ONE: break;
    case BLEND_SRC_COLOR:
    case BLEND_INV_SRC_COLOR: s.input = in.src0[channel]; break;
    case BLEND_SRC_ALPHA:
    case BLEND_INV_SRC_ALPHA: s.input = in.src0[kAlpha]; break;
    case BLEND_DEST_ALPHA:
    case BLEND_INV_DEST_ALPHA: s.input = in.dest[kAlpha]; break;
    case BLEND_DEST_COLOR:
    case BLEND_INV_DEST_COLOR: s.input = in.dest[channel]; break;
    case BLEND_SRC_ALPHA_SAT:
      if (channel == kAlpha) return {BLEND_ONE, 0.0f, 0.0f};  // (f,f,f,1): the alpha factor is the constant 1
      s.input = in.src0[kAlpha];
      s.input2 = in.dest[kAlpha];
      break;
    case BLEND_BLEND_FACTOR:
    case BLEND_INV_BLEND_FACTOR: s.input = in.factor[channel]; break;
    case BLEND_SRC1_COLOR:
    case BLEND_INV_SRC1_COLOR: s.input = in.src1[channel]; break;
    case BLEND_SRC1_ALPHA:
    case BLEND_INV_SRC1_ALPHA: s.input = in.src1[kAlpha]; break;
  }
  return s;
}

// The factor D3D11_BLEND `blend` gives for `channel` (FS 17.1, the enum comments).
float Factor(BLEND blend, int channel, const BlenderInputs& in) {
  switch (blend) {
    case BLEND_ZERO: return 0.0f;
    case BLEND_ONE: return 1.0f;
    case BLEND_SRC_COLOR: return in.src0[channel];
    case BLEND_INV_SRC_COLOR: return 1.0f - in.src0[channel];
    case BLEND_SRC_ALPHA: return in.src0[kAlpha];
    case BLEND_INV_SRC_ALPHA: return 1.0f - in.src0[kAlpha];
    case BLEND_DEST_ALPHA: return in.dest[kAlpha];
    case BLEND_INV_DEST_ALPHA: return 1.0f - in.dest[kAlpha];
    case BLEND_DEST_COLOR: return in.dest[channel];
    case BLEND_INV_DEST_COLOR: return 1.0f - in.dest[channel];
    // (f,f,f,1), f = min(1 - RT(N).a, oN.a) (FS 17.1); the Saturated reading
    // clamps f to [0, 1] (SatReading, blend.h).
    case BLEND_SRC_ALPHA_SAT:
      if (channel == kAlpha) return 1.0f;
      return in.sat == SatReading::Saturated ? Saturate(SrcAlphaSat(in)) : SrcAlphaSat(in);
    case BLEND_BLEND_FACTOR: return in.factor[channel];
    case BLEND_INV_BLEND_FACTOR: return 1.0f - in.factor[channel];
    case BLEND_SRC1_COLOR: return in.src1[channel];
    case BLEND_INV_SRC1_COLOR: return 1.0f - in.src1[channel];
    case BLEND_SRC1_ALPHA: return in.src1[kAlpha];
    case BLEND_INV_SRC1_ALPHA: return 1.0f - in.src1[kAlpha];
  }
  return 0.0f;  // not a D3D11_BLEND: CreateBlendState would have refused it
}

// One channel of Src*SrcFactor OP Dest*DestFactor. MIN and MAX ignore the
// factors and behave like the min/max shader instructions (FS 17.1).
// The products are recorded in `terms` (channel `c`) for the tolerance model.
float Combine(BLEND_OP op, float src, float srcFactor, float dest, float destFactor, BlendTerms& terms,
              int c) {
  terms.srcFactor[c] = srcFactor;
  terms.destFactor[c] = destFactor;
  const float srcTerm = src * srcFactor;
  const float destTerm = dest * destFactor;
  const bool arithmetic = op == BLEND_OP_ADD || op == BLEND_OP_SUBTRACT || op == BLEND_OP_REV_SUBTRACT;
  terms.srcTerm[c] = arithmetic ? srcTerm : 0.0f;
  terms.destTerm[c] = arithmetic ? destTerm : 0.0f;
  terms.arithmetic[c] = arithmetic;
  terms.srcOperand[c] = src;
  terms.destOperand[c] = dest;
  float result = 0.0f;
  switch (op) {
    case BLEND_OP_ADD: result = srcTerm + destTerm; break;
    case BLEND_OP_SUBTRACT: result = srcTerm - destTerm; break;
    case BLEND_OP_REV_SUBTRACT: result = destTerm - srcTerm; break;
    case BLEND_OP_MIN: result = std::fmin(src, dest); break;
    case BLEND_OP_MAX: result = std::fmax(src, dest); break;
  }
  terms.result[c] = result;
  return result;
}

// The blended colour before conversion to the target format; Encode then clamps
// it to the target's range (FS 17.5: "there is a clamp to the RenderTarget range
// after blend") and quantises it.
BlenderInputs Inputs(DXGI_FORMAT format, const Float4& blendFactor, const Float4& src0, const Float4& src1,
                     const StoredColor& dest, SatReading sat) {
  return {EnterBlender(format, src0), EnterBlender(format, src1), Decode(format, dest),
          EnterBlender(format, blendFactor), sat};
}

Float4 Blend(DXGI_FORMAT format, const RENDER_TARGET_BLEND_DESC& blend, const Float4& blendFactor,
             const Float4& src0, const Float4& src1, const StoredColor& dest, SatReading sat, BlendTerms& terms) {
  const BlenderInputs in = Inputs(format, blendFactor, src0, src1, dest, sat);
  Float4 result{};
  for (int c = 0; c < kAlpha; ++c) {
    result[c] = Combine(blend.BlendOp, in.src0[c], Factor(blend.SrcBlend, c, in), in.dest[c],
                        Factor(blend.DestBlend, c, in), terms, c);
    terms.srcFactorSource[c] = SourceOf(blend.SrcBlend, c, in);
    terms.destFactorSource[c] = SourceOf(blend.DestBlend, c, in);
  }
  result[kAlpha] = Combine(blend.BlendOpAlpha, in.src0[kAlpha], Factor(blend.SrcBlendAlpha, kAlpha, in),
                           in.dest[kAlpha], Factor(blend.DestBlendAlpha, kAlpha, in), terms, kAlpha);
  terms.srcFactorSource[kAlpha] = SourceOf(blend.SrcBlendAlpha, kAlpha, in);
  terms.destFactorSource[kAlpha] = SourceOf(blend.DestBlendAlpha, kAlpha, in);
  for (float& channel : result) channel = FlushDenorm(channel);
  return result;
}

// FS 17.15: masked-off channels keep what the target held.
StoredColor ApplyWriteMask(UINT8 writeMask, const StoredColor& written, const StoredColor& dest) {
  StoredColor result = dest;
  for (int c = 0; c < 4; ++c) {
    if ((writeMask & (1u << c)) != 0) result.bits[c] = written.bits[c];
  }
  return result;
}

}  // namespace

BlendReading BlendReadingOf(DXGI_FORMAT format, const RENDER_TARGET_BLEND_DESC& blend, const Float4& blendFactor,
                            const Float4& src0, const Float4& src1, const StoredColor& dest, SatReading sat) {
  // Integer targets are never blended; BlendEnable FALSE writes the converted source.
  const bool blends = blend.BlendEnable != FALSE && !IsUintFormat(format);
  BlendTerms terms;
  const Float4 color = blends ? Blend(format, blend, blendFactor, src0, src1, dest, sat, terms) : src0;
  const StoredColor stored = ApplyWriteMask(blend.RenderTargetWriteMask, Encode(format, color), dest);
  for (int c = 0; c < 4; ++c) {
    // Channels the format lacks and masked channels were not written by the blender.
    const bool written = (blend.RenderTargetWriteMask & (1u << c)) != 0 && KindOf(format, c) != ChannelKind::Absent;
    if (!written) terms.arithmetic[c] = false;
  }
  return {stored, Decode(format, stored), terms};
}

BlendOutput BlendResult(DXGI_FORMAT format, const RENDER_TARGET_BLEND_DESC& blend,
                        const Float4& blendFactor, const Float4& src0, const Float4& src1,
                        const StoredColor& dest) {
  BlendOutput out;
  static_cast<BlendReading&>(out) = BlendReadingOf(format, blend, blendFactor, src0, src1, dest, SatReading::Formula);
  // The Saturated reading differs only where a blended, written colour channel
  // uses SRC_ALPHA_SAT (its alpha factor is the constant 1) and f is outside [0, 1].
  bool satUsed = false;
  for (int c = 0; c < kAlpha; ++c) {
    satUsed = satUsed || (out.terms.arithmetic[c] &&
                          (blend.SrcBlend == BLEND_SRC_ALPHA_SAT || blend.DestBlend == BLEND_SRC_ALPHA_SAT));
  }
  if (satUsed) {
    const float f = SrcAlphaSat(Inputs(format, blendFactor, src0, src1, dest, SatReading::Formula));
    if (!(f >= 0.0f && f <= 1.0f)) {
      out.hasSaturatedReading = true;
      out.saturated = BlendReadingOf(format, blend, blendFactor, src0, src1, dest, SatReading::Saturated);
    }
  }
  return out;
}

const RENDER_TARGET_BLEND_DESC& TargetBlendDesc(const BLEND_DESC& desc, UINT renderTarget) {
  if (renderTarget >= SIMULTANEOUS_RENDER_TARGET_COUNT) {
    throw std::out_of_range("rhi::reference: render target index above 7");
  }
  return desc.IndependentBlendEnable != FALSE ? desc.RenderTarget[renderTarget] : desc.RenderTarget[0];
}

BlendOutput BlendResult(DXGI_FORMAT format, const BLEND_DESC& desc, UINT renderTarget,
                        const Float4& blendFactor, const Float4& src0, const Float4& src1,
                        const StoredColor& dest) {
  return BlendResult(format, TargetBlendDesc(desc, renderTarget), blendFactor, src0, src1, dest);
}

}  // namespace rhi::reference
