// The translucent objects of the demos, created by the scenes (scenes.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/meshes.h"
#include "renderer/particle_system.h"
#include "renderer/translucent_object.h"

namespace renderer {

// What every object is made with.
struct ObjectSetup {
  rhi::Device* device = nullptr;
  uint32_t seed = 0;
  glm::vec3 lightDir{0, 1, 0};  // towards the light
};

// Billboards of a ParticleSystem's particles, lit through a normal-mapped puff
// (shaders_hlsl/smoke.fx); fire: the flame ramp, and additive blending for OVER.
std::unique_ptr<TranslucentObject> CreateSmoke(const ObjectSetup& setup, const ParticleSettings& particles, bool fire,
                                               std::string* error);

// `count` instanced glass shards (shaders_hlsl/shards.fx) in a box over the floor.
struct ShardSettings {
  uint32_t count = 0;
  float surfaceTint = 0.5f;  // 0: neutral surface colour (tint only in transmission)
  bool allRed = false;       // every shard transmits (1, 0.15, 0.15)
};
std::unique_ptr<TranslucentObject> CreateShards(const ObjectSetup& setup, const ShardSettings& shards,
                                                std::string* error);

// Translucent triangle meshes (shaders_hlsl/meshes.fx) in one vertex and index
// buffer, lit two-sided; back to front sorts their triangles (meshes.cpp says when
// that is exact).
std::unique_ptr<TranslucentObject> CreateMeshes(const ObjectSetup& setup, const std::vector<TriangleMesh>& meshes,
                                                std::string* error);

// Deferred shading (shaders_hlsl/oit/common.fxh, deferred.hlsli), shared by the objects:
// a raw view (ByteAddressBuffer) of the first `bytes` of `buffer` (a multiple of 4),
// which needs RESOURCE_MISC_BUFFER_ALLOW_RAW_VIEWS and BIND_SHADER_RESOURCE on it;
bool CreateRawView(rhi::Device* device, rhi::Buffer* buffer, uint32_t bytes, rhi::ComPtr<rhi::ShaderResourceView>* out);
// deferred.hlsli's InvViewProj, which the objects set with their ViewProj (every pass
// of theirs can unproject);
void SetInverseViewProj(fx::Effect* effect, const Camera& camera);
// and the resolve's full-screen triangle (Draw(3, 0), no vertex buffer) with `pass` of
// `technique` (null: the first) of `effect`, after setting deferred.hlsli's FrameSize
// from the frame.
bool DrawFullscreenPass(rhi::DeviceContext* context, fx::Effect* effect, const oit::FrameDesc& frame,
                        const char* technique, const char* pass, std::string* error);

}  // namespace renderer
