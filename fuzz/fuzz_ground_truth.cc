// Fuzz target: the ground-truth and intrinsics parsers on the same bytes: KITTI poses.txt and
// calib.txt, a Middlebury *_par.txt, a Strecha *.camera file (alone and as a folder), the
// intrinsics file reader (fx fy cx cy / K / P, also COLMAP- and OpenCV-style numbers), the
// calibration-file reader of --intrinsics (the same bytes as an OpenCV FileStorage .yml and .xml,
// as a COLMAP cameras.txt and as plain numbers), a NeRF transforms.json and the format detection.
// comic::Error is the expected answer to bad bytes.
#include <filesystem>

#include "fuzz/fuzz_input.h"
#include "io/core/error.h"
#include "io/datasets/camera_calibration_file.h"
#include "io/datasets/ground_truth_cameras.h"
#include "io/datasets/kitti_odometry.h"
#include "io/datasets/nerf_transforms.h"

namespace {

template <class F>
void Expect(F&& f) {
  try {
    f();
  } catch (const comic::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace comic::io;
  const std::string path = comic::fuzz::WriteInput("poses.txt", data, size);
  const std::string folder = comic::fuzz::ScratchDir() + "/strecha";
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  const std::string camera = comic::fuzz::WriteInput("strecha/0000.png.camera", data, size);
  Expect([&] { ReadKittiPoses(path); });
  Expect([&] { ReadKittiIntrinsics(path, 0); });
  Expect([&] { ReadKittiProjection(path, 2); });
  Expect([&] { ReadIntrinsicsFile(path); });
  Expect([&] { ReadMiddleburyParFile(path); });
  Expect([&] { ReadStrechaCameraFile(camera); });
  Expect([&] { ReadStrechaCameraFolder(folder); });
  Expect([&] { DetectGroundTruthFormat(path); });
  Expect([&] { ReadGroundTruthCameras(path); });
  Expect([&] { ReadKittiGroundTruth(path, path); });
  const std::string transforms = comic::fuzz::WriteInput("transforms.json", data, size);
  Expect([&] { ReadNerfTransforms(transforms); });
  Expect([&] { ReadGroundTruthCameras(transforms); });
  for (const char* name : {"calib.yml", "calib.xml", "cameras.txt", "calib.txt"}) {
    const std::string calibration = comic::fuzz::WriteInput(name, data, size);
    Expect([&] { ReadCameraCalibrationFile(calibration); });
  }
  return 0;
}
