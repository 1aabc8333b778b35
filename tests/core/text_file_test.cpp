// Bounded reading of the text files users name, and the UTF-8 check, against
// hand-made byte sequences.
#include "servoloop/core/text_file.hpp"

#include <string>

#include <gtest/gtest.h>

#include "servoloop/core/errors.hpp"
#include "temp_dir.hpp"

namespace servoloop {
namespace {

std::string errorOf(const std::filesystem::path& path, std::uintmax_t limit = kMaxTextFileBytes) {
  try {
    readTextFile(path, "URDF file", limit);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(TextFile, ReadsARegularFileWhole) {
  testing::TempDir dir("servoloop-text-file");
  const std::string text = "<robot name=\"r\">\n  <link name=\"a\"/>\n</robot>\n";
  testing::writeFile(dir.path() / "r.urdf", text);
  EXPECT_EQ(readTextFile(dir.path() / "r.urdf", "URDF file"), text);
}

TEST(TextFile, RefusesWhatIsNotARegularFileBeforeReading) {
  testing::TempDir dir("servoloop-text-file");
  EXPECT_EQ(errorOf("/dev/zero"),
            "/dev/zero: is not a regular file (a device, FIFO or socket), so it is not read; give the path of a "
            "URDF file");
  EXPECT_EQ(errorOf(dir.path()), dir.path().string() + ": is a folder, not a URDF file");
  EXPECT_EQ(errorOf(dir.path() / "none.urdf"), (dir.path() / "none.urdf").string() + ": URDF file not found; check the path");
}

TEST(TextFile, RefusesFilesOverTheLimit) {
  testing::TempDir dir("servoloop-text-file");
  testing::writeFile(dir.path() / "big.urdf", std::string((3u << 20) + 1, 'x'));
  EXPECT_EQ(errorOf(dir.path() / "big.urdf", 3u << 20),
            (dir.path() / "big.urdf").string() + ": URDF file of 3 MiB; the limit is 3 MiB");
  EXPECT_EQ(readTextFile(dir.path() / "big.urdf", "URDF file", 4u << 20).size(), (3u << 20) + 1);
}

TEST(TextFile, Utf8CheckFindsTheFirstBadByte) {
  EXPECT_EQ(invalidUtf8Offset("plain ASCII"), std::nullopt);
  EXPECT_EQ(invalidUtf8Offset("N\xC2\xB7m, \xE2\x80\x94, \xF0\x9F\xA4\x96"), std::nullopt);  // N·m, em dash, U+1F916
  EXPECT_EQ(invalidUtf8Offset("ab\xFF"), 2u);                                                // never in UTF-8
  EXPECT_EQ(invalidUtf8Offset("a\xC0\xAF"), 1u);                                             // overlong '/'
  EXPECT_EQ(invalidUtf8Offset("a\xED\xA0\x80"), 1u);                                         // UTF-16 surrogate
  EXPECT_EQ(invalidUtf8Offset("abc\xE2\x80"), 3u);                                           // cut short
  EXPECT_EQ(invalidUtf8Offset("\xF4\x90\x80\x80"), 0u);                                      // past U+10FFFF
  EXPECT_EQ(invalidUtf8Offset("x\xC3(y"), 1u);                                               // bad continuation
}

}  // namespace
}  // namespace servoloop
