// The particle spawn/kill rule of the GPU particle system (document 000),
// shared by the update geometry shader and, line for line, by the CPU model in
// renderer/particle_rule.h: both must agree on every particle.

// Integer hash (Wang): deterministic on the CPU and the GPU.
uint ParticleHash(uint x) {
  x = (x ^ 61u) ^ (x >> 16);
  x *= 9u;
  x = x ^ (x >> 4);
  x *= 0x27d4eb2du;
  x = x ^ (x >> 15);
  return x;
}

// The seed of child `slot` spawned by emitter `emitterSeed` in update `frame`.
uint ChildSeed(uint emitterSeed, uint frame, uint slot, uint spawnPerFrame) {
  return ParticleHash(emitterSeed * 0x9E3779B9u + frame * spawnPerFrame + slot);
}

// A child lives `minLife + seed % lifeRange` updates.
uint ChildLifetime(uint seed, uint minLife, uint lifeRange) { return minLife + seed % lifeRange; }
