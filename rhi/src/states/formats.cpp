#include "states/formats.h"

#include <array>

namespace rhi::states {
namespace {

enum Traits : uint8_t { kNone = 0, kAlpha = 1, kAlphaOne = 2, kSrgb = 4, kDepth = 8, kStencil = 16 };

constexpr UINT VB = BIND_VERTEX_BUFFER;
constexpr UINT IB = BIND_INDEX_BUFFER;
constexpr UINT SR = BIND_SHADER_RESOURCE;
constexpr UINT RT = BIND_RENDER_TARGET;
constexpr UINT DS = BIND_DEPTH_STENCIL;
constexpr UINT UA = BIND_UNORDERED_ACCESS;
constexpr UINT kColor = SR | RT | UA;        // typeless colour families
constexpr UINT kVertexColor = VB | kColor;  // the common typed colour formats

constexpr FormatInfo Make(DXGI_FORMAT format, const char* name, VkFormat vk, uint8_t bytes, uint8_t components,
                          ComponentKind kind, UINT binds, DXGI_FORMAT family, uint8_t traits = kNone,
                          ViewSwizzle swizzle = ViewSwizzle::Identity) {
  return FormatInfo{format,
                    name,
                    vk,
                    bytes,
                    components,
                    kind,
                    (traits & kAlpha) != 0,
                    (traits & kAlphaOne) != 0,
                    (traits & kSrgb) != 0,
                    (traits & kDepth) != 0,
                    (traits & kStencil) != 0,
                    binds,
                    family,
                    swizzle};
}

constexpr FormatInfo MakeBlockCompressed(DXGI_FORMAT format, const char* name, VkFormat vk, uint8_t blockBytes,
                                         uint8_t components, ComponentKind kind, DXGI_FORMAT family,
                                         uint8_t traits = kNone) {
  FormatInfo info = Make(format, name, vk, blockBytes, components, kind, SR, family, traits);
  info.blockSize = 4;
  return info;
}

#define F(fmt) DXGI_FORMAT_##fmt, "DXGI_FORMAT_" #fmt
#define VK(fmt) VK_FORMAT_##fmt
#define FAM(fmt) DXGI_FORMAT_##fmt
using K = ComponentKind;

// Bind flags follow "Format Support for Direct3D Feature Level 11.0 Hardware"
// (required support only). Typeless formats list what a resource of that format
// may be bound as (through typed views).
constexpr FormatInfo kFormats[] = {
    Make(F(R32G32B32A32_TYPELESS), VK(R32G32B32A32_UINT), 16, 4, K::Typeless, kColor, FAM(R32G32B32A32_TYPELESS), kAlpha),
    Make(F(R32G32B32A32_FLOAT), VK(R32G32B32A32_SFLOAT), 16, 4, K::Float, kVertexColor, FAM(R32G32B32A32_TYPELESS), kAlpha),
    Make(F(R32G32B32A32_UINT), VK(R32G32B32A32_UINT), 16, 4, K::Uint, kVertexColor, FAM(R32G32B32A32_TYPELESS), kAlpha),
    Make(F(R32G32B32A32_SINT), VK(R32G32B32A32_SINT), 16, 4, K::Sint, kVertexColor, FAM(R32G32B32A32_TYPELESS), kAlpha),
    // 96-bit: render target and UAV use are optional at FL11_0.
    Make(F(R32G32B32_TYPELESS), VK(R32G32B32_UINT), 12, 3, K::Typeless, SR, FAM(R32G32B32_TYPELESS)),
    Make(F(R32G32B32_FLOAT), VK(R32G32B32_SFLOAT), 12, 3, K::Float, VB | SR, FAM(R32G32B32_TYPELESS)),
    Make(F(R32G32B32_UINT), VK(R32G32B32_UINT), 12, 3, K::Uint, VB | SR, FAM(R32G32B32_TYPELESS)),
    Make(F(R32G32B32_SINT), VK(R32G32B32_SINT), 12, 3, K::Sint, VB | SR, FAM(R32G32B32_TYPELESS)),
    Make(F(R16G16B16A16_TYPELESS), VK(R16G16B16A16_UINT), 8, 4, K::Typeless, kColor, FAM(R16G16B16A16_TYPELESS), kAlpha),
    Make(F(R16G16B16A16_FLOAT), VK(R16G16B16A16_SFLOAT), 8, 4, K::Float, kVertexColor, FAM(R16G16B16A16_TYPELESS), kAlpha),
    Make(F(R16G16B16A16_UNORM), VK(R16G16B16A16_UNORM), 8, 4, K::Unorm, kVertexColor, FAM(R16G16B16A16_TYPELESS), kAlpha),
    Make(F(R16G16B16A16_UINT), VK(R16G16B16A16_UINT), 8, 4, K::Uint, kVertexColor, FAM(R16G16B16A16_TYPELESS), kAlpha),
    Make(F(R16G16B16A16_SNORM), VK(R16G16B16A16_SNORM), 8, 4, K::Snorm, kVertexColor, FAM(R16G16B16A16_TYPELESS), kAlpha),
    Make(F(R16G16B16A16_SINT), VK(R16G16B16A16_SINT), 8, 4, K::Sint, kVertexColor, FAM(R16G16B16A16_TYPELESS), kAlpha),
    Make(F(R32G32_TYPELESS), VK(R32G32_UINT), 8, 2, K::Typeless, kColor, FAM(R32G32_TYPELESS)),
    Make(F(R32G32_FLOAT), VK(R32G32_SFLOAT), 8, 2, K::Float, kVertexColor, FAM(R32G32_TYPELESS)),
    Make(F(R32G32_UINT), VK(R32G32_UINT), 8, 2, K::Uint, kVertexColor, FAM(R32G32_TYPELESS)),
    Make(F(R32G32_SINT), VK(R32G32_SINT), 8, 2, K::Sint, kVertexColor, FAM(R32G32_TYPELESS)),
    // DXGI packs R in the low bits, which Vulkan calls A2B10G10R10.
    Make(F(R10G10B10A2_TYPELESS), VK(A2B10G10R10_UINT_PACK32), 4, 4, K::Typeless, kColor, FAM(R10G10B10A2_TYPELESS), kAlpha),
    Make(F(R10G10B10A2_UNORM), VK(A2B10G10R10_UNORM_PACK32), 4, 4, K::Unorm, kVertexColor, FAM(R10G10B10A2_TYPELESS), kAlpha),
    Make(F(R10G10B10A2_UINT), VK(A2B10G10R10_UINT_PACK32), 4, 4, K::Uint, kVertexColor, FAM(R10G10B10A2_TYPELESS), kAlpha),
    Make(F(R11G11B10_FLOAT), VK(B10G11R11_UFLOAT_PACK32), 4, 3, K::Float, kVertexColor, FAM(UNKNOWN)),
    Make(F(R8G8B8A8_TYPELESS), VK(R8G8B8A8_UINT), 4, 4, K::Typeless, kColor, FAM(R8G8B8A8_TYPELESS), kAlpha),
    Make(F(R8G8B8A8_UNORM), VK(R8G8B8A8_UNORM), 4, 4, K::Unorm, kVertexColor, FAM(R8G8B8A8_TYPELESS), kAlpha),
    Make(F(R8G8B8A8_UNORM_SRGB), VK(R8G8B8A8_SRGB), 4, 4, K::Unorm, SR | RT, FAM(R8G8B8A8_TYPELESS), kAlpha | kSrgb),
    Make(F(R8G8B8A8_UINT), VK(R8G8B8A8_UINT), 4, 4, K::Uint, kVertexColor, FAM(R8G8B8A8_TYPELESS), kAlpha),
    Make(F(R8G8B8A8_SNORM), VK(R8G8B8A8_SNORM), 4, 4, K::Snorm, kVertexColor, FAM(R8G8B8A8_TYPELESS), kAlpha),
    Make(F(R8G8B8A8_SINT), VK(R8G8B8A8_SINT), 4, 4, K::Sint, kVertexColor, FAM(R8G8B8A8_TYPELESS), kAlpha),
    Make(F(R16G16_TYPELESS), VK(R16G16_UINT), 4, 2, K::Typeless, kColor, FAM(R16G16_TYPELESS)),
    Make(F(R16G16_FLOAT), VK(R16G16_SFLOAT), 4, 2, K::Float, kVertexColor, FAM(R16G16_TYPELESS)),
    Make(F(R16G16_UNORM), VK(R16G16_UNORM), 4, 2, K::Unorm, kVertexColor, FAM(R16G16_TYPELESS)),
    Make(F(R16G16_UINT), VK(R16G16_UINT), 4, 2, K::Uint, kVertexColor, FAM(R16G16_TYPELESS)),
    Make(F(R16G16_SNORM), VK(R16G16_SNORM), 4, 2, K::Snorm, kVertexColor, FAM(R16G16_TYPELESS)),
    Make(F(R16G16_SINT), VK(R16G16_SINT), 4, 2, K::Sint, kVertexColor, FAM(R16G16_TYPELESS)),
    // R32 family: colour image by default, D32_SFLOAT when bound as depth.
    Make(F(R32_TYPELESS), VK(R32_UINT), 4, 1, K::Typeless, kColor | DS, FAM(R32_TYPELESS)),
    Make(F(D32_FLOAT), VK(D32_SFLOAT), 4, 1, K::Depth, DS, FAM(R32_TYPELESS), kDepth),
    Make(F(R32_FLOAT), VK(R32_SFLOAT), 4, 1, K::Float, kVertexColor, FAM(R32_TYPELESS)),
    Make(F(R32_UINT), VK(R32_UINT), 4, 1, K::Uint, kVertexColor | IB, FAM(R32_TYPELESS)),
    Make(F(R32_SINT), VK(R32_SINT), 4, 1, K::Sint, kVertexColor, FAM(R32_TYPELESS)),
    // R24G8 family: always a depth image in Vulkan (no colour format aliases it).
    Make(F(R24G8_TYPELESS), VK(D24_UNORM_S8_UINT), 4, 2, K::Typeless, SR | DS, FAM(R24G8_TYPELESS), kDepth | kStencil),
    Make(F(D24_UNORM_S8_UINT), VK(D24_UNORM_S8_UINT), 4, 2, K::Depth, DS, FAM(R24G8_TYPELESS), kDepth | kStencil),
    Make(F(R24_UNORM_X8_TYPELESS), VK(D24_UNORM_S8_UINT), 4, 1, K::Unorm, SR, FAM(R24G8_TYPELESS), kDepth),
    // The stencil read of an R24G8 texture: a view of the image's stencil aspect.
    Make(F(X24_TYPELESS_G8_UINT), VK(D24_UNORM_S8_UINT), 4, 1, K::Uint, SR, FAM(R24G8_TYPELESS), kStencil,
         ViewSwizzle::StencilInGreen),
    Make(F(R8G8_TYPELESS), VK(R8G8_UINT), 2, 2, K::Typeless, kColor, FAM(R8G8_TYPELESS)),
    Make(F(R8G8_UNORM), VK(R8G8_UNORM), 2, 2, K::Unorm, kVertexColor, FAM(R8G8_TYPELESS)),
    Make(F(R8G8_UINT), VK(R8G8_UINT), 2, 2, K::Uint, kVertexColor, FAM(R8G8_TYPELESS)),
    Make(F(R8G8_SNORM), VK(R8G8_SNORM), 2, 2, K::Snorm, kVertexColor, FAM(R8G8_TYPELESS)),
    Make(F(R8G8_SINT), VK(R8G8_SINT), 2, 2, K::Sint, kVertexColor, FAM(R8G8_TYPELESS)),
    // R16 family: colour image by default, D16_UNORM when bound as depth.
    Make(F(R16_TYPELESS), VK(R16_UINT), 2, 1, K::Typeless, kColor | DS, FAM(R16_TYPELESS)),
    Make(F(R16_FLOAT), VK(R16_SFLOAT), 2, 1, K::Float, kVertexColor, FAM(R16_TYPELESS)),
    Make(F(D16_UNORM), VK(D16_UNORM), 2, 1, K::Depth, DS, FAM(R16_TYPELESS), kDepth),
    Make(F(R16_UNORM), VK(R16_UNORM), 2, 1, K::Unorm, kVertexColor, FAM(R16_TYPELESS)),
    Make(F(R16_UINT), VK(R16_UINT), 2, 1, K::Uint, kVertexColor | IB, FAM(R16_TYPELESS)),
    Make(F(R16_SNORM), VK(R16_SNORM), 2, 1, K::Snorm, kVertexColor, FAM(R16_TYPELESS)),
    Make(F(R16_SINT), VK(R16_SINT), 2, 1, K::Sint, kVertexColor, FAM(R16_TYPELESS)),
    Make(F(R8_TYPELESS), VK(R8_UINT), 1, 1, K::Typeless, kColor, FAM(R8_TYPELESS)),
    Make(F(R8_UNORM), VK(R8_UNORM), 1, 1, K::Unorm, kVertexColor, FAM(R8_TYPELESS)),
    Make(F(R8_UINT), VK(R8_UINT), 1, 1, K::Uint, kVertexColor, FAM(R8_TYPELESS)),
    Make(F(R8_SNORM), VK(R8_SNORM), 1, 1, K::Snorm, kVertexColor, FAM(R8_TYPELESS)),
    Make(F(R8_SINT), VK(R8_SINT), 1, 1, K::Sint, kVertexColor, FAM(R8_TYPELESS)),
    Make(F(A8_UNORM), VK(R8_UNORM), 1, 1, K::Unorm, SR | RT, FAM(UNKNOWN), kAlpha, ViewSwizzle::AlphaFromRed),
    // Block-compressed formats: shader resources only (no render target, UAV or
    // buffer use in D3D11); each family has a typeless member for typed views.
    MakeBlockCompressed(F(BC1_TYPELESS), VK(BC1_RGBA_UNORM_BLOCK), 8, 4, K::Typeless, FAM(BC1_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC1_UNORM), VK(BC1_RGBA_UNORM_BLOCK), 8, 4, K::Unorm, FAM(BC1_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC1_UNORM_SRGB), VK(BC1_RGBA_SRGB_BLOCK), 8, 4, K::Unorm, FAM(BC1_TYPELESS), kAlpha | kSrgb),
    MakeBlockCompressed(F(BC2_TYPELESS), VK(BC2_UNORM_BLOCK), 16, 4, K::Typeless, FAM(BC2_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC2_UNORM), VK(BC2_UNORM_BLOCK), 16, 4, K::Unorm, FAM(BC2_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC2_UNORM_SRGB), VK(BC2_SRGB_BLOCK), 16, 4, K::Unorm, FAM(BC2_TYPELESS), kAlpha | kSrgb),
    MakeBlockCompressed(F(BC3_TYPELESS), VK(BC3_UNORM_BLOCK), 16, 4, K::Typeless, FAM(BC3_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC3_UNORM), VK(BC3_UNORM_BLOCK), 16, 4, K::Unorm, FAM(BC3_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC3_UNORM_SRGB), VK(BC3_SRGB_BLOCK), 16, 4, K::Unorm, FAM(BC3_TYPELESS), kAlpha | kSrgb),
    MakeBlockCompressed(F(BC4_TYPELESS), VK(BC4_UNORM_BLOCK), 8, 1, K::Typeless, FAM(BC4_TYPELESS)),
    MakeBlockCompressed(F(BC4_UNORM), VK(BC4_UNORM_BLOCK), 8, 1, K::Unorm, FAM(BC4_TYPELESS)),
    MakeBlockCompressed(F(BC4_SNORM), VK(BC4_SNORM_BLOCK), 8, 1, K::Snorm, FAM(BC4_TYPELESS)),
    MakeBlockCompressed(F(BC5_TYPELESS), VK(BC5_UNORM_BLOCK), 16, 2, K::Typeless, FAM(BC5_TYPELESS)),
    MakeBlockCompressed(F(BC5_UNORM), VK(BC5_UNORM_BLOCK), 16, 2, K::Unorm, FAM(BC5_TYPELESS)),
    MakeBlockCompressed(F(BC5_SNORM), VK(BC5_SNORM_BLOCK), 16, 2, K::Snorm, FAM(BC5_TYPELESS)),
    // BGRA (DXGI 1.1). X8 formats live in B8G8R8A8 images with the alpha hidden.
    Make(F(B8G8R8A8_UNORM), VK(B8G8R8A8_UNORM), 4, 4, K::Unorm, VB | SR | RT, FAM(B8G8R8A8_TYPELESS), kAlpha),
    Make(F(B8G8R8X8_UNORM), VK(B8G8R8A8_UNORM), 4, 3, K::Unorm, SR | RT, FAM(B8G8R8X8_TYPELESS), kAlphaOne,
         ViewSwizzle::AlphaOne),
    Make(F(B8G8R8A8_TYPELESS), VK(B8G8R8A8_UNORM), 4, 4, K::Typeless, SR | RT, FAM(B8G8R8A8_TYPELESS), kAlpha),
    Make(F(B8G8R8A8_UNORM_SRGB), VK(B8G8R8A8_SRGB), 4, 4, K::Unorm, SR | RT, FAM(B8G8R8A8_TYPELESS), kAlpha | kSrgb),
    Make(F(B8G8R8X8_TYPELESS), VK(B8G8R8A8_UNORM), 4, 3, K::Typeless, SR | RT, FAM(B8G8R8X8_TYPELESS), kAlphaOne,
         ViewSwizzle::AlphaOne),
    Make(F(B8G8R8X8_UNORM_SRGB), VK(B8G8R8A8_SRGB), 4, 3, K::Unorm, SR | RT, FAM(B8G8R8X8_TYPELESS), kAlphaOne | kSrgb,
         ViewSwizzle::AlphaOne),

    // BC6H and BC7 (D3D11): numbered after the BGRA formats.
    MakeBlockCompressed(F(BC6H_TYPELESS), VK(BC6H_UFLOAT_BLOCK), 16, 3, K::Typeless, FAM(BC6H_TYPELESS)),
    MakeBlockCompressed(F(BC6H_UF16), VK(BC6H_UFLOAT_BLOCK), 16, 3, K::Float, FAM(BC6H_TYPELESS)),
    MakeBlockCompressed(F(BC6H_SF16), VK(BC6H_SFLOAT_BLOCK), 16, 3, K::Float, FAM(BC6H_TYPELESS)),
    MakeBlockCompressed(F(BC7_TYPELESS), VK(BC7_UNORM_BLOCK), 16, 4, K::Typeless, FAM(BC7_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC7_UNORM), VK(BC7_UNORM_BLOCK), 16, 4, K::Unorm, FAM(BC7_TYPELESS), kAlpha),
    MakeBlockCompressed(F(BC7_UNORM_SRGB), VK(BC7_SRGB_BLOCK), 16, 4, K::Unorm, FAM(BC7_TYPELESS), kAlpha | kSrgb),
};

#undef F
#undef VK
#undef FAM

constexpr UINT kMaxFormat = DXGI_FORMAT_BC7_UNORM_SRGB;

// Index by enum value, built once.
const std::array<const FormatInfo*, kMaxFormat + 1>& Lookup() {
  static const auto table = [] {
    std::array<const FormatInfo*, kMaxFormat + 1> t{};
    for (const FormatInfo& f : kFormats) t[f.format] = &f;
    return t;
  }();
  return table;
}

constexpr VkFormat kD24S8Candidates[] = {VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT_S8_UINT};
// D32_SFLOAT is not mandatory as a depth attachment (X8_D24 or D32 is); the
// stencil variant keeps 32-bit float precision.
constexpr VkFormat kD32Candidates[] = {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D32_SFLOAT_S8_UINT};
constexpr VkFormat kD16Candidates[] = {VK_FORMAT_D16_UNORM};  // mandatory

}  // namespace

const FormatInfo* GetFormatInfo(DXGI_FORMAT format) {
  return format <= kMaxFormat ? Lookup()[format] : nullptr;
}

std::span<const FormatInfo> AllFormats() { return kFormats; }

const char* FormatName(DXGI_FORMAT format) {
  const FormatInfo* info = GetFormatInfo(format);
  return info ? info->name : nullptr;
}

VkComponentMapping ToVkComponentMapping(ViewSwizzle swizzle) {
  constexpr VkComponentSwizzle I = VK_COMPONENT_SWIZZLE_IDENTITY;
  switch (swizzle) {
    case ViewSwizzle::Identity: return {I, I, I, I};
    case ViewSwizzle::AlphaOne: return {I, I, I, VK_COMPONENT_SWIZZLE_ONE};
    case ViewSwizzle::StencilInGreen:
      return {VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_R, VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_ONE};
    case ViewSwizzle::AlphaFromRed:
      return {VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_R};
  }
  return {I, I, I, I};
}

bool IsViewCompatible(DXGI_FORMAT resource, DXGI_FORMAT view) {
  const FormatInfo* r = GetFormatInfo(resource);
  const FormatInfo* v = GetFormatInfo(view);
  if (!r || !v || v->kind == ComponentKind::Typeless) return false;
  if (r->kind != ComponentKind::Typeless) return resource == view;
  return v->family == resource;
}

std::span<const VkFormat> DepthFormatCandidates(DXGI_FORMAT format) {
  const FormatInfo* info = GetFormatInfo(format);
  if (!info) return {};
  switch (info->family) {
    case DXGI_FORMAT_R24G8_TYPELESS: return kD24S8Candidates;
    case DXGI_FORMAT_R32_TYPELESS: return kD32Candidates;
    case DXGI_FORMAT_R16_TYPELESS: return kD16Candidates;
    default: return {};
  }
}

VkFormat PickDepthFormat(DXGI_FORMAT format, const std::function<bool(VkFormat)>& isSupported) {
  for (VkFormat candidate : DepthFormatCandidates(format)) {
    if (isSupported(candidate)) return candidate;
  }
  return VK_FORMAT_UNDEFINED;
}

}  // namespace rhi::states
