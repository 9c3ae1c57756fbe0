// The particle of the GPU particle system (document 000) as it travels the
// pipeline: one point, in the stream-output buffers' layout (40 bytes).
struct Particle {
  float3 origin : ORIGIN;       // p0: where it was born
  float3 velocity : VELOCITY;   // v0
  uint2 seedAge : SEEDAGE;      // x: seed, y: age in updates
  uint2 kindLife : KINDLIFE;    // x: 0 emitter / 1 smoke; y: lifetime in updates
};
