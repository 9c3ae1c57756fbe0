// The patches applied one after another, in the order the backend uses them:
// reflect, link locations, stream output, SV_InstanceID, point size, strip.
#include <gtest/gtest.h>

#include <set>
#include <spirv/unified1/spirv.hpp11>

#include "spirv/patches.h"
#include "spirv/stream_output.h"
#include "test_compiler.h"
#include "test_util.h"

namespace {

using namespace rhi::spirv;

std::vector<uint32_t> Ok(const WordsResult& result) {
  EXPECT_TRUE(result.ok()) << result.error;
  return result.value;
}

TEST(SpirvCombined, VertexShaderThroughEveryPatch) {
  const char* source = R"(
struct VSOut { float4 pos : SV_Position; uint id : BLENDINDICES0; float3 n : NORMAL; };
VSOut main(float4 pos : POSITION, float3 n : NORMAL, uint iid : SV_InstanceID) {
  VSOut o;
  o.pos = pos;
  o.id = iid;
  o.n = n;
  return o;
})";
  std::vector<uint32_t> words = spirv_test::Legalize(spirv_test::Compile(source, spirv_test::Stage::Vertex));
  Result<Reflection> reflected = Reflect(words);
  ASSERT_TRUE(reflected.ok()) << reflected.error;
  const uint32_t idLocation = *reflected->FindOutput("BLENDINDICES", 0)->location;
  const uint32_t normalLocation = *reflected->FindOutput("NORMAL", 0)->location;

  // Link: NORMAL0 -> location 7, BLENDINDICES0 -> 6; reflect again for the new locations.
  words = Ok(RemapLocations(words, StorageClass::Output, {{normalLocation, 7}, {idLocation, 6}}));
  reflected = Reflect(words);
  ASSERT_TRUE(reflected.ok()) << reflected.error;
  EXPECT_EQ(reflected->FindOutput("NORMAL", 0)->location, 7u);
  EXPECT_EQ(reflected->FindOutput("BLENDINDICES", 0)->scalarKind, ScalarKind::UInt);

  const std::vector<rhi::SO_DECLARATION_ENTRY> entries = {{0, "BLENDINDICES", 0, 0, 1, 0},
                                                          {0, "NORMAL", 0, 2, 1, 0}};
  words = Ok(ApplyStreamOutput(words, *reflected, entries, {}));
  words = Ok(RebaseInstanceIndex(words));
  words = Ok(AddPointSizeOutput(words));
  words = Ok(StripHlslDecorations(words));
  EXPECT_VALID_SPIRV(words);

  const Reflection final = Reflect(words).value;
  EXPECT_TRUE(final.writesPointSize);
  std::set<uint32_t> xfbLocations;
  for (const InterfaceVariable& v : final.outputs) {
    const auto offset =
        spirv_test::DecorationOf(words, v.variableId, static_cast<uint32_t>(spv::Decoration::Offset));
    if (!offset) continue;
    xfbLocations.insert(*v.location);
    EXPECT_EQ(v.scalarKind, v.location == 8u ? ScalarKind::UInt : ScalarKind::Float);
    EXPECT_EQ(*offset, v.location == 8u ? 0u : 4u);
  }
  EXPECT_EQ(xfbLocations, (std::set<uint32_t>{8, 9})) << "captures go past the remapped locations";
}

}  // namespace
