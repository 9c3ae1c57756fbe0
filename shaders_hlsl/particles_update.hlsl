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

Particle VSPassThrough(Particle p) { return p; }

float3 RandomDirection(uint seed) {
  uint3 bits = uint3(ParticleHash(seed + 1u), ParticleHash(seed + 2u), ParticleHash(seed + 3u));
  return float3(bits & 0xFFFFu) / 65535.0 * 2.0 - 1.0;
}

[maxvertexcount(17)]
void GSUpdate(point Particle input[1], inout PointStream<Particle> stream) {
  Particle p = input[0];
  p.seedAge.y += 1;
  if (p.kindLife.x == 0) {
    stream.Append(p);  // emitters live forever
    for (uint slot = 0; slot < SpawnPerFrame; ++slot) {
      Particle child;
      uint seed = ChildSeed(p.seedAge.x, Frame, slot, SpawnPerFrame);
      child.origin = p.origin;
      child.velocity = RandomDirection(seed) * Spread + float3(0, SpeedUp, 0);
      child.seedAge = uint2(seed, 0);
      child.kindLife = uint2(1, ChildLifetime(seed, MinLife, LifeRange));
      stream.Append(child);
    }
  } else if (p.seedAge.y < p.kindLife.y) {
    stream.Append(p);
  }
}

