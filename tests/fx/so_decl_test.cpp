#include "fx/so_decl.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fx {
namespace {

StreamOutputDecl MustParse(const std::vector<std::string>& streams) {
  auto r = StreamOutputDecl::Parse(streams);
  if (auto* e = std::get_if<SoDeclError>(&r)) {
    ADD_FAILURE() << "stream " << e->stream << " offset " << e->offset << ": " << e->message;
    return {};
  }
  return std::get<StreamOutputDecl>(std::move(r));
}

SoDeclError MustFail(const std::vector<std::string>& streams) {
  auto r = StreamOutputDecl::Parse(streams);
  if (std::holds_alternative<StreamOutputDecl>(r)) {
    ADD_FAILURE() << "expected an error";
    return {};
  }
  return std::get<SoDeclError>(r);
}

void ExpectEntry(const rhi::SO_DECLARATION_ENTRY& e, rhi::UINT stream, const char* name, rhi::UINT index,
                 int start, int count, int slot) {
  EXPECT_EQ(e.Stream, stream);
  if (name == nullptr) {
    EXPECT_EQ(e.SemanticName, nullptr);
  } else {
    ASSERT_NE(e.SemanticName, nullptr);
    EXPECT_STREQ(e.SemanticName, name);
  }
  EXPECT_EQ(e.SemanticIndex, index);
  EXPECT_EQ(e.StartComponent, start);
  EXPECT_EQ(e.ComponentCount, count);
  EXPECT_EQ(e.OutputSlot, slot);
}

TEST(SoDecl, SemanticsIndicesMasksSlotsAndGaps) {
  StreamOutputDecl d = MustParse({" POSITION.xyz; 1 : TEXCOORD3.zw ;$SKIP.xy;COLOR.rgba; NORMAL1; ;2:$SKIP"});
  const auto& e = d.Entries();
  ASSERT_EQ(e.size(), 6u);
  ExpectEntry(e[0], 0, "POSITION", 0, 0, 3, 0);
  ExpectEntry(e[1], 0, "TEXCOORD", 3, 2, 2, 1);
  ExpectEntry(e[2], 0, nullptr, 0, 0, 2, 0);
  ExpectEntry(e[3], 0, "COLOR", 0, 0, 4, 0);
  ExpectEntry(e[4], 0, "NORMAL", 1, 0, 4, 0);
  ExpectEntry(e[5], 0, nullptr, 0, 0, 4, 2);
  auto strides = d.Strides();
  EXPECT_EQ(strides[0], (3 + 2 + 4 + 4) * 4u);
  EXPECT_EQ(strides[1], 2 * 4u);
  EXPECT_EQ(strides[2], 4 * 4u);
  EXPECT_EQ(strides[3], 0u);
}

TEST(SoDecl, FourStreams) {
  StreamOutputDecl d = MustParse({"SV_Position.xyzw", "", "1:TEXCOORD0.y", "2:DATA.w"});
  const auto& e = d.Entries();
  ASSERT_EQ(e.size(), 3u);
  ExpectEntry(e[0], 0, "SV_Position", 0, 0, 4, 0);
  ExpectEntry(e[1], 2, "TEXCOORD", 0, 1, 1, 1);
  ExpectEntry(e[2], 3, "DATA", 0, 3, 1, 2);
}

TEST(SoDecl, EmptyDeclarationsDeclareNothing) {
  EXPECT_TRUE(MustParse({""}).Empty());
  EXPECT_TRUE(MustParse({" ; ;; "}).Empty());
  EXPECT_TRUE(MustParse({}).Empty());
}

TEST(SoDecl, SemanticStorageSurvivesCopiesAndMoves) {
  std::vector<std::string> streams = {"LONG_SEMANTIC_NAME_BEYOND_SMALL_STRINGS0.xy; P.x"};
  StreamOutputDecl copy;
  {
    StreamOutputDecl original = MustParse(streams);
    copy = original;
    StreamOutputDecl moved = std::move(original);
    EXPECT_STREQ(moved.Entries()[1].SemanticName, "P");
  }
  streams.clear();
  ASSERT_EQ(copy.Entries().size(), 2u);
  EXPECT_STREQ(copy.Entries()[0].SemanticName, "LONG_SEMANTIC_NAME_BEYOND_SMALL_STRINGS");
  EXPECT_STREQ(copy.Entries()[1].SemanticName, "P");
}

TEST(SoDecl, Errors) {
  SoDeclError e = MustFail({"POSITION.xz"});
  EXPECT_EQ(e.offset, 9u);
  EXPECT_EQ(e.message, "mask '.xz' must name contiguous components in order");

  e = MustFail({"POSITION.zy"});
  EXPECT_EQ(e.message, "mask '.zy' must name contiguous components in order");

  e = MustFail({"POSITION; COLOR.xq"});
  EXPECT_EQ(e.offset, 16u);
  EXPECT_EQ(e.message, "invalid mask '.xq' (use xyzw or rgba)");

  e = MustFail({"POSITION", "4:COLOR"});
  EXPECT_EQ(e.stream, 1u);
  EXPECT_EQ(e.offset, 0u);
  EXPECT_EQ(e.message, "output slot 4 is out of range (0-3)");

  e = MustFail({":COLOR"});
  EXPECT_EQ(e.message, "missing output slot before ':'");

  e = MustFail({"1x:COLOR"});
  EXPECT_EQ(e.message, "a semantic name cannot start with a digit");

  e = MustFail({"POSITION; $GAP.x"});
  EXPECT_EQ(e.offset, 10u);
  EXPECT_EQ(e.message, "unknown token '$GAP' (only $SKIP starts with '$')");

  e = MustFail({"$SKIP.3"});
  EXPECT_EQ(e.message, "unexpected '3' in stream-output entry");

  e = MustFail({"POSITION COLOR"});
  EXPECT_EQ(e.offset, 9u);
  EXPECT_EQ(e.message, "unexpected 'C' in stream-output entry");

  e = MustFail({"1:POSITION", "1:COLOR"});
  EXPECT_EQ(e.stream, 1u);
  EXPECT_EQ(e.message, "output slot 1 is already written by stream 0");

  e = MustFail({"A", "B", "C", "D", "E"});
  EXPECT_EQ(e.message, "at most 4 stream-output declarations");
}

}  // namespace
}  // namespace fx
