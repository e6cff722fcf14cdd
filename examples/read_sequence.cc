// Example: read a frame sequence as comic-sfm does and print the mean grey level of each frame.
//
//   build/examples/example_read_sequence examples/data/kitti06_000-011/image_l
#include <iostream>
#include <opencv2/core.hpp>

#include "io/core/error.h"
#include "io/image/image_sequence.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " FRAMES\n";
    return 2;
  }
  try {
    comic::io::ImageSequenceOptions options;  // defaults: original size, every frame
    const auto sequence = comic::io::ImageSequence::Open(argv[1], options);
    for (size_t i = 0; i < sequence.NumFrames(); ++i) {
      const comic::io::Frame frame = sequence.ReadFrame(i);  // 8-bit grey + BGR colour
      std::cout << frame.name << "  mean grey " << cv::mean(frame.gray)[0] << "\n";
    }
  } catch (const comic::Error& e) {  // every bad input arrives as one clear comic::Error
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
