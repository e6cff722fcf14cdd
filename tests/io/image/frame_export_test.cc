#include "io/image/frame_export.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace comic::io {
namespace {

using comic::test::ScopedTempDir;

// A 64x48 MJPG clip (the codec every Debian OpenCV build writes) of `count` frames whose colour
// encodes the frame number.
std::string WriteClip(const ScopedTempDir& dir, int count) {
  const std::string video = dir.File("clip.avi");
  cv::VideoWriter writer(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(64, 48),
                         true);
  EXPECT_TRUE(writer.isOpened());
  for (int id = 0; id < count; ++id) {
    writer.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(id * 40, 200 - id * 30, 90)));
  }
  return video;
}

TEST(FrameExport, WritesEverySelectedFrameOnceAsTheDecodedPng) {
  ScopedTempDir dir;
  const std::string video = WriteClip(dir, 5);
  ImageSequenceOptions options;
  options.first_frame = 1;
  options.stride = 2;  // frames 1, 3
  const ImageSequence sequence = ImageSequence::Open(video, options);
  std::vector<std::pair<size_t, size_t>> calls;
  WriteSequenceFrames(sequence, dir.File("images"),
                      [&](size_t done, size_t all) { calls.emplace_back(done, all); });
  EXPECT_EQ(ListFiles(dir.File("images")),
            (std::vector<std::string>{"frame_000001.png", "frame_000003.png"}));
  EXPECT_EQ(calls, (std::vector<std::pair<size_t, size_t>>{{1, 2}, {2, 2}}));
  for (size_t i = 0; i < sequence.NumFrames(); ++i) {
    // PNG is lossless: the file holds exactly the decoded frame the tracker saw.
    const cv::Mat written = cv::imread(dir.File("images/" + sequence.FrameNames()[i]));
    const cv::Mat decoded = sequence.ReadFrame(i).color;
    ASSERT_EQ(written.size(), decoded.size());
    EXPECT_EQ(cv::norm(written, decoded, cv::NORM_INF), 0.0) << i;
  }
}

TEST(FrameExport, WritesTheResizedFramesTheModelIsFor) {
  ScopedTempDir dir;
  ImageSequenceOptions options;
  options.resize_height = 24;
  const ImageSequence sequence = ImageSequence::Open(WriteClip(dir, 2), options);
  WriteSequenceFrames(sequence, dir.File("images"));
  EXPECT_EQ(cv::imread(dir.File("images/frame_000000.png")).size(), cv::Size(32, 24));
}

TEST(FrameExport, RefusesAFolderOfImages) {
  ScopedTempDir dir;
  cv::imwrite(dir.File("a.png"), cv::Mat(30, 40, CV_8UC1, cv::Scalar(7)));
  const ImageSequence sequence = ImageSequence::Open(dir.path());
  try {
    WriteSequenceFrames(sequence, dir.File("images"));
    FAIL() << "expected comic::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidArgument);
    EXPECT_NE(std::string(e.what()).find("folder of images already"), std::string::npos);
  }
  EXPECT_FALSE(PathExists(dir.File("images")));
}

}  // namespace
}  // namespace comic::io
