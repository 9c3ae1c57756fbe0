// The update pass of the GPU particle system (document 000): a geometry shader
// ages, spawns and kills particles and streams the survivors out. Nothing is
// rasterized. (The draw pass lives in its own file: glslang 12 crashes on a
// file holding geometry shaders with different output stream types.)
#include "particle.hlsli"
#include "particle_rule.hlsli"

cbuffer UpdateParams : register(b0) {
  uint Frame;          // index of this update, from 1
  uint SpawnPerFrame;  // children per emitter per update
  uint MinLife;
  uint LifeRange;
  float3 Spread;       // random initial velocity range
  float SpeedUp;       // initial upward speed
};

#include "particle_update.hlsli"

