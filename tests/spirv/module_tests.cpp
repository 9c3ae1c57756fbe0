// The word-stream reader/editor and the typed editing helpers.
#include <gtest/gtest.h>

#include "shaders.h"
#include "spirv/module_editor.h"
#include "spirv/spirv_module.h"
#include "test_compiler.h"
#include "test_util.h"

namespace {

using rhi::spirv::DecodeString;
using rhi::spirv::Editor;
using rhi::spirv::EncodeString;
using rhi::spirv::Instruction;
using rhi::spirv::Module;
using rhi::spirv::OpOf;
using spirv_test::Compile;
using spirv_test::Stage;

constexpr auto Op(spv::Op op) { return static_cast<uint32_t>(op); }

Module ParseOrDie(const std::vector<uint32_t>& words) {
  auto parsed = Module::Parse(words);
  EXPECT_TRUE(parsed.ok()) << parsed.error;
  return std::move(parsed.value);
}

TEST(SpirvStrings, EncodePadsWithAtLeastOneNul) {
  EXPECT_EQ(EncodeString("abc"), (std::vector<uint32_t>{0x00636261u}));
  EXPECT_EQ(EncodeString("main"), (std::vector<uint32_t>{0x6e69616du, 0u}));
  EXPECT_EQ(EncodeString(""), (std::vector<uint32_t>{0u}));
}

TEST(SpirvStrings, DecodeReportsWordsUsed) {
  const std::vector<uint32_t> words = {0x6e69616du, 0x00000000u, 0xdeadbeefu};
  size_t used = 0;
  EXPECT_EQ(DecodeString(words, &used), "main");
  EXPECT_EQ(used, 2u);
  const std::vector<uint32_t> text = EncodeString("SV_POSITION");
  EXPECT_EQ(DecodeString(text, &used), "SV_POSITION");
  EXPECT_EQ(used, 3u);
}

TEST(SpirvModule, ParseAssembleRoundTrips) {
  const std::vector<uint32_t> words = Compile(spirv_test::shaders::kVertex, Stage::Vertex);
  const Module module = ParseOrDie(words);
  EXPECT_EQ(module.Assemble(), words);
  EXPECT_EQ(module.version(), 0x00010500u);
  EXPECT_EQ(module.bound(), words[3]);
  EXPECT_EQ(OpOf(module[0]), spv::Op::OpCapability);
}

TEST(SpirvModule, ParseRejectsBadInput) {
  EXPECT_NE(Module::Parse(std::vector<uint32_t>{1, 2, 3}).error, "");
  EXPECT_NE(Module::Parse(std::vector<uint32_t>{0xdeadbeef, 0x10500, 0, 10, 0}).error.find("magic"), std::string::npos);
  // An OpCapability claiming 3 words with only 2 present.
  const auto truncated = Module::Parse(std::vector<uint32_t>{0x07230203, 0x10500, 0, 10, 0, (3u << 16) | 17u, 1u});
  EXPECT_NE(truncated.error.find("truncated"), std::string::npos) << truncated.error;
}

TEST(SpirvModule, ResultIdsAndTypesFollowTheGrammar) {
  const Instruction variable(Op(spv::Op::OpVariable), {7, 9, 3});
  EXPECT_EQ(variable.resultType(), 7u);
  EXPECT_EQ(variable.resultId(), 9u);
  const Instruction type(Op(spv::Op::OpTypeFloat), {4, 32});
  EXPECT_EQ(type.resultId(), 4u);
  EXPECT_EQ(type.resultType(), 0u);
  const Instruction store(Op(spv::Op::OpStore), {4, 5});
  EXPECT_EQ(store.resultId(), 0u);
}

TEST(SpirvModule, InsertRemoveAndNewId) {
  Module module = ParseOrDie(Compile(spirv_test::shaders::kVertex, Stage::Vertex));
  const size_t before = module.size();
  const uint32_t bound = module.bound();
  EXPECT_EQ(module.NewId(), bound);
  EXPECT_EQ(module.bound(), bound + 1);

  EXPECT_EQ(module.Insert(1, {Instruction(Op(spv::Op::OpNop), {}), Instruction(Op(spv::Op::OpNop), {})}), 3u);
  EXPECT_EQ(module.size(), before + 2);
  EXPECT_EQ(OpOf(module[1]), spv::Op::OpNop);
  EXPECT_EQ(module.FindOpcode(Op(spv::Op::OpNop)), 1u);
  EXPECT_EQ(module.RemoveIf([](const Instruction& i) { return OpOf(i) == spv::Op::OpNop; }), 2u);
  EXPECT_EQ(module.size(), before);
  EXPECT_EQ(module.Assemble()[3], module.bound()) << "the header carries the raised bound";
}

TEST(SpirvModule, InstructionOperandEditingKeepsWordCount) {
  Instruction inst(Op(spv::Op::OpEntryPoint), {0, 4});
  for (uint32_t w : EncodeString("main")) inst.appendOperand(w);
  inst.appendOperand(11);
  EXPECT_EQ(inst.words[0] >> 16, inst.words.size());
  size_t next = 0;
  EXPECT_EQ(inst.stringAt(2, &next), "main");
  EXPECT_EQ(next, 4u);
  EXPECT_EQ(inst.operand(next), 11u);
}

TEST(SpirvEditor, ReusesTypesAndKeepsModuleValid) {
  const std::vector<uint32_t> words = Compile(spirv_test::shaders::kVertex, Stage::Vertex);
  Module module = ParseOrDie(words);
  Editor editor(module);
  const size_t size = module.size();
  const uint32_t f32 = editor.TypeFloat(32);
  const uint32_t v4 = editor.TypeVector(f32, 4);
  EXPECT_EQ(module.size(), size) << "float and float4 exist already";
  EXPECT_EQ(OpOf(*module.Definition(v4)), spv::Op::OpTypeVector);

  // New declarations go before the first function, in layout order.
  const uint32_t f16 = editor.TypeFloat(16);
  const uint32_t half = editor.ConstantF32(0.5f);
  const uint32_t pointer = editor.TypePointer(spv::StorageClass::Private, f32);
  const uint32_t var = editor.AddGlobalVariable(pointer, spv::StorageClass::Private);
  editor.AddName(var, "added");
  editor.Decorate(var, spv::Decoration::RelaxedPrecision);
  editor.AddCapability(spv::Capability::Float16);
  editor.AddCapability(spv::Capability::Float16);
  editor.AddToInterface(var);
  editor.AddToInterface(var);
  EXPECT_NE(f16, f32);
  EXPECT_EQ(editor.ConstantF32(0.5f), half);
  EXPECT_LT(module.FindDefinition(var), module.FindOpcode(Op(spv::Op::OpFunction)));
  EXPECT_TRUE(editor.HasCapability(spv::Capability::Float16));
  const auto interface = editor.Interface(editor.EntryPoint());
  EXPECT_EQ(std::count(interface.begin(), interface.end(), var), 1);
  EXPECT_TRUE(editor.HasFlagDecoration(var, spv::Decoration::RelaxedPrecision));

  const std::vector<uint32_t> edited = module.Assemble();
  EXPECT_EQ(spirv_test::CountOpcode(edited, Op(spv::Op::OpCapability)),
            spirv_test::CountOpcode(words, Op(spv::Op::OpCapability)) + 1);
  EXPECT_VALID_SPIRV(edited);
}

TEST(SpirvEditor, EntryPointAndFunctionBody) {
  Module module = ParseOrDie(Compile(spirv_test::shaders::kVertex, Stage::Vertex));
  Editor editor(module);
  const auto entry = editor.EntryPoint();
  EXPECT_EQ(entry.model, spv::ExecutionModel::Vertex);
  EXPECT_EQ(entry.name, "main");
  EXPECT_EQ(editor.Interface(entry).size(), 7u);  // 4 inputs, 3 outputs
  const auto [start, end] = editor.FunctionRange(entry.function);
  ASSERT_NE(start, Module::npos);
  EXPECT_EQ(OpOf(module[end]), spv::Op::OpFunctionEnd);
  const size_t body = editor.FunctionBodyStart(entry.function);
  EXPECT_GT(body, start);
  EXPECT_LT(body, end);
  EXPECT_NE(OpOf(module[body]), spv::Op::OpVariable);
  EXPECT_EQ(OpOf(module[body - 1]), spv::Op::OpVariable);  // glslang's wrapper declares locals first
}

}  // namespace
