// FNV-1a 64 against its published test vectors, files hashed as their bytes, the hex form.
#include "io/core/content_hash.h"

#include <gtest/gtest.h>

#include <string>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

TEST(ContentHash, MatchesFnv1a64TestVectors) {
  EXPECT_EQ(HashBytes(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(HashBytes("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(HashBytes("foobar"), 0x85944171f73967e8ull);
}

TEST(ContentHash, PiecesHashAsTheWhole) {
  ContentHash pieces;
  pieces.Add("foo");
  pieces.Add("bar");
  EXPECT_EQ(pieces.value(), HashBytes("foobar"));
}

TEST(ContentHash, AFileHashesAsItsBytes) {
  test::ScopedTempDir dir;
  // More than one read block, so that the blocks are chained.
  std::string bytes(3 << 20, 'x');
  bytes[12345] = '\0';
  bytes.back() = 'y';
  WriteFileAtomically(dir.File("f.bin"), bytes);
  ContentHash hash;
  hash.AddFile(dir.File("f.bin"));
  EXPECT_EQ(hash.value(), HashBytes(bytes));
  try {
    hash.AddFile(dir.File("missing.bin"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kNotFound);
    EXPECT_NE(std::string(e.what()).find("missing.bin"), std::string::npos);
  }
}

TEST(ContentHash, HexDigitsAreSixteenLowerCase) {
  EXPECT_EQ(HexDigits(0), "0000000000000000");
  EXPECT_EQ(HexDigits(0xcbf29ce484222325ull), "cbf29ce484222325");
}

}  // namespace
}  // namespace comic::io
