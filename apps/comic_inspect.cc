// comic_inspect: opens a frame sequence the way every comic-sfm app does and reports what it
// sees (frame count, sizes, names), optionally writing a contact sheet of sampled frames.
#include <algorithm>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "apps/common/arg_parser.h"
#include "apps/common/frame_range_flags.h"
#include "apps/common/input_budget_flags.h"
#include "apps/common/shared_flags.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/core/protected_inputs.h"
#include "io/image/image_io.h"
#include "io/image/image_sequence.h"

namespace {

int Run(int argc, char** argv) {
  std::string input;
  std::string sheet_path;
  int sheet_frames = 6;
  comic::io::ImageSequenceOptions options;
  comic::apps::ArgParser parser(
      "comic_inspect", "FRAMES [options]",
      "Opens FRAMES (a folder of images, a single image or a video file) as comic-sfm reads it\n"
      "and prints the number of frames, their size and names.");
  parser.AddPositional("FRAMES", "folder of images, image or video file", &input);
  comic::apps::AddResizeHeightFlag(parser, &options.resize_height);
  comic::apps::AddFrameRangeFlags(parser, &options);
  parser.AddOption("contact-sheet", "PNG", "write a contact sheet of sampled frames", &sheet_path);
  parser.AddOption("sheet-frames", "N", "number of frames on the contact sheet (1-100)",
                   &sheet_frames);
  comic::apps::AddAllowTruncatedFlag(parser, &options.allow_truncated);
  if (parser.Parse(argc, argv) == comic::apps::ArgParser::Result::kHelpShown) return 0;
  comic::io::CheckResizeHeight(options.resize_height);  // by its flag's name
  COMIC_CHECK(sheet_frames >= 1 && sheet_frames <= 100, kInvalidArgument,
              "--sheet-frames must be >= 1 and <= 100, got " << sheet_frames);
  comic::io::CheckOutputsAvoidInputs({{"--contact-sheet", sheet_path}}, {{"FRAMES", input}});
  if (!sheet_path.empty()) comic::io::CheckWritableFile(sheet_path);
  if (!sheet_path.empty()) comic::io::CheckImageOutputFormat(sheet_path, "--contact-sheet");

  const auto sequence = comic::io::ImageSequence::Open(input, options);
  comic::apps::PrintWarning("comic_inspect", sequence.warning());
  std::cout << "source:      " << input << (sequence.IsVideo() ? " (video)" : " (images)") << "\n"
            << "frames:      " << sequence.NumFrames() << "\n"
            << "stored size: " << sequence.SourceFrameSize().width << "x"
            << sequence.SourceFrameSize().height << "\n"
            << "frame size:  " << sequence.FrameSize().width << "x" << sequence.FrameSize().height
            << "\n"
            << "first:       " << sequence.FrameNames().front() << "\n"
            << "last:        " << sequence.FrameNames().back() << "\n";

  if (!sheet_path.empty()) {
    const size_t n = std::min<size_t>(sheet_frames, sequence.NumFrames());
    const int tile_h = 160;
    std::vector<cv::Mat> tiles;
    for (size_t k = 0; k < n; ++k) {
      const size_t index = n == 1 ? 0 : k * (sequence.NumFrames() - 1) / (n - 1);
      const comic::io::Frame frame = sequence.ReadFrame(index);
      cv::Mat tile;
      const int tile_w = std::max(1, frame.color.cols * tile_h / frame.color.rows);
      cv::resize(frame.color, tile, cv::Size(tile_w, tile_h), 0, 0, cv::INTER_AREA);
      cv::putText(tile, frame.name, {4, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 255, 255}, 1,
                  cv::LINE_AA);
      tiles.push_back(tile);
    }
    cv::Mat sheet;
    cv::hconcat(tiles, sheet);
    comic::io::WriteImageAtomically(sheet_path, sheet);
    std::cout << "wrote:       " << sheet_path << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return comic::apps::RunMain("comic_inspect", [&] { return Run(argc, argv); });
}
