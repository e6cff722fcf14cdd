// The EXIF focal prior of a folder of photos: the frames read must agree within 1 %, frames
// without EXIF are skipped, implausible values and disagreement give none with a reason.
#include "sfm/run/exif_focal_prior.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <vector>

#include "tests/io/image/exif_test_jpeg.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

using comic::test::ExifTestTags;

// One 64x48 JPEG per entry: its FocalLengthIn35mmFilm, or no EXIF for 0.
void WriteFrames(const std::string& folder, const std::vector<int>& focal_35mm) {
  for (size_t i = 0; i < focal_35mm.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "/%06zu.jpg", i);
    std::ofstream file(folder + name, std::ios::binary);
    if (focal_35mm[i] == 0) {
      file << comic::test::SmallJpeg();
      continue;
    }
    ExifTestTags tags;
    tags.focal_length_35mm = static_cast<uint16_t>(focal_35mm[i]);
    file << comic::test::WithExifSegment(comic::test::SmallJpeg(),
                                         comic::test::ExifTiff(tags, i % 2 == 1));
  }
}

ExifFocalPrior PriorOf(const std::vector<int>& focal_35mm, ExifFocalPriorOptions options = {}) {
  comic::test::ScopedTempDir dir;
  WriteFrames(dir.path(), focal_35mm);
  return FindExifFocalPrior(io::ImageSequence::Open(dir.path()), options);
}

TEST(ExifFocalPrior, FramesThatAgreeGiveTheFocalInPixels) {
  const ExifFocalPrior prior = PriorOf({28, 28, 28});
  ASSERT_TRUE(prior.focal_px.has_value());
  EXPECT_DOUBLE_EQ(*prior.focal_px, 28.0 / 35.0 * 64);
  EXPECT_EQ(prior.description,
            "EXIF FocalLengthIn35mmFilm 28 mm in 000000.jpg, 3 of 3 frames read agree");
  EXPECT_EQ(prior.frames_read, 3u);
  EXPECT_EQ(prior.frames_with_focal, 3u);
  // Within 1 %: 100 and 101 mm agree, 100 and 102 do not.
  EXPECT_TRUE(PriorOf({100, 101}).focal_px.has_value());
  EXPECT_FALSE(PriorOf({100, 102}).focal_px.has_value());
}

TEST(ExifFocalPrior, FramesWithoutExifAreSkipped) {
  const ExifFocalPrior prior = PriorOf({0, 28, 0, 28});
  ASSERT_TRUE(prior.focal_px.has_value());
  EXPECT_DOUBLE_EQ(*prior.focal_px, 28.0 / 35.0 * 64);
  EXPECT_EQ(prior.description,
            "EXIF FocalLengthIn35mmFilm 28 mm in 000001.jpg, 2 of 4 frames read agree");
  const ExifFocalPrior none = PriorOf({0, 0});
  EXPECT_FALSE(none.focal_px.has_value());
  EXPECT_TRUE(none.description.empty());
  EXPECT_EQ(none.frames_read, 2u);
}

TEST(ExifFocalPrior, DisagreementAndImplausibleValuesGiveNoneWithTheReason) {
  const ExifFocalPrior disagree = PriorOf({28, 28, 50});
  EXPECT_FALSE(disagree.focal_px.has_value());
  EXPECT_EQ(disagree.description,
            "EXIF focal lengths disagree: 51.2 px (000000.jpg) and 91.4 px (000002.jpg)");
  const ExifFocalPrior huge = PriorOf({65535});
  EXPECT_FALSE(huge.focal_px.has_value());
  EXPECT_NE(huge.description.find("not a plausible focal length for 64x48 frames"),
            std::string::npos)
      << huge.description;
}

TEST(ExifFocalPrior, ReadsAFewFramesSpreadOverTheSequence) {
  ExifFocalPriorOptions options;
  options.max_frames = 3;
  // Frames 0, 4 and 9 of ten are read: frame 9 disagrees, the others are never looked at.
  const ExifFocalPrior prior = PriorOf({28, 50, 50, 50, 28, 50, 50, 50, 50, 40}, options);
  EXPECT_EQ(prior.frames_read, 3u);
  EXPECT_NE(prior.description.find("000009.jpg"), std::string::npos) << prior.description;
}

}  // namespace
}  // namespace comic::sfm
