// The six shader stages' resource-binding methods of DeviceContext as a table, so
// that code which saves, restores or tests every stage's bindings (deferred
// contexts, state save and restore as imgui_impl_dx11 does it) walks one list
// instead of spelling VS, HS, DS, GS, PS and CS out six times. Built on the public
// API only.
#pragma once

#include "rhi/rhi.h"

namespace rhi {

struct StageMethods {
  const char* name;  // "VS" ... "CS"
  void (DeviceContext::*setConstantBuffers)(UINT, UINT, Buffer* const*);
  void (DeviceContext::*getConstantBuffers)(UINT, UINT, Buffer**);
  void (DeviceContext::*setShaderResources)(UINT, UINT, ShaderResourceView* const*);
  void (DeviceContext::*getShaderResources)(UINT, UINT, ShaderResourceView**);
  void (DeviceContext::*setSamplers)(UINT, UINT, SamplerState* const*);
  void (DeviceContext::*getSamplers)(UINT, UINT, SamplerState**);
};

#define RHI_STAGE_METHODS(Prefix)                                                                    \
  StageMethods {                                                                                     \
    #Prefix, &DeviceContext::Prefix##SetConstantBuffers, &DeviceContext::Prefix##GetConstantBuffers, \
        &DeviceContext::Prefix##SetShaderResources, &DeviceContext::Prefix##GetShaderResources,      \
        &DeviceContext::Prefix##SetSamplers, &DeviceContext::Prefix##GetSamplers                     \
  }
// In pipeline order: VS, HS, DS, GS, PS, then CS.
inline constexpr StageMethods kStageMethods[6] = {RHI_STAGE_METHODS(VS), RHI_STAGE_METHODS(HS),
                                                  RHI_STAGE_METHODS(DS), RHI_STAGE_METHODS(GS),
                                                  RHI_STAGE_METHODS(PS), RHI_STAGE_METHODS(CS)};
#undef RHI_STAGE_METHODS

}  // namespace rhi
