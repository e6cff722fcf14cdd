// The bad-input matrix (issue 19) as one data-driven test: every row is an app, its arguments, the
// exit code it must give and words its one stderr line must hold. Each row runs against a fixture
// folder made here (corrupt, truncated, empty and mismatched images, garbage and truncated
// videos, short and garbage ground truth, files where folders are expected, an existing
// database), and the fixture folder, where every row's outputs would go, must be unchanged
// afterwards: the same files, sizes and checksums, no output folder, no hidden temp file.
// New apps and options add rows to kCases.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace {

namespace fs = std::filesystem;
using comic::test::AppPath;
using comic::test::CountLines;
using comic::test::ExampleDir;
using comic::test::ScopedTempDir;

// Seconds a row may take: the slowest rows run a short reconstruction.
constexpr int kRowTimeoutSeconds = 120;

// {d} = the fixture folder, {e} = the bundled example's frames, {x} = the bundled example.
struct Case {
  const char* app;
  const char* args;
  int exit_code;
  std::vector<const char*> words;
  // Above 0: the row runs under `ulimit -v` of this many MB, so that its work runs out of memory.
  int memory_limit_mb = 0;
};

// clang-format off
const std::vector<Case> kCases = {
  // comic_detect
  {"comic_detect", "{d}/missing.png", 1, {"missing.png", "no such file"}},
  {"comic_detect", "{d}/empty.png", 1, {"empty.png", "cannot decode"}},
  {"comic_detect", "{d}/garbage.png", 1, {"garbage.png", "cannot decode"}},
  {"comic_detect", "{d}/truncated.png", 1, {"truncated.png", "truncated"}},
  {"comic_detect", "{d}/truncated.jpg", 1, {"truncated.jpg", "truncated"}},
  {"comic_detect", "{d}/frames", 1, {"frames", "is a folder"}},
  {"comic_detect", "{d}/good.png --resize-height 100000", 2, {"--resize-height", "100000"}},
  // Issue 29: the docs' range [8, 16384] held in the sequences only; comic_detect took 1.
  {"comic_detect", "{d}/good.png --resize-height 1", 2, {"--resize-height", "[8, 16384]"}},
  {"comic_detect", "{d}/good.png --scale 1e9", 2, {"scale", "1e+09"}},
  {"comic_detect", "{d}/good.png --scale 0", 2, {"scale"}},
  {"comic_detect", "{d}/good.png --scale nan", 2, {"scale", "nan"}},
  {"comic_detect", "{d}/good.png --delta 1000", 2, {"delta", "1000"}},
  {"comic_detect", "{d}/good.png --half-length 100000", 2, {"--half-length", "100000"}},
  {"comic_detect", "{d}/good.png --block-size 100000", 2, {"--block-size"}},
  {"comic_detect", "{d}/good.png --threads 100000", 2, {"--threads", "hardware"}},
  {"comic_detect", "{d}/good.png --threads -1", 2, {"--threads"}},
  {"comic_detect", "{d}/good.png --max-pixels 1000", 1, {"good.png", "--max-pixels"}},
  {"comic_detect", "{d}/good.png --max-pixels 0", 2, {"--max-pixels"}},
  {"comic_detect", "{d}/good.png --min-cornerness 0.3", 2, {"--min-cornerness"}},
  // Issue 29: messages named library fields, one of them the old flag --radius.
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --search-radius -1", 2,
   {"--search-radius must be > 0"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --window 0", 2, {"--window must be >= 1"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --first -1", 2, {"--first must be >= 0"}},
  {"comic_detect", "{d}/good.png --max-features -1", 2, {"--max-features"}},
  {"comic_detect", "{d}/good.png --overlay {d}/o.png --json /proc/features.json", 1,
   {"/proc/features.json"}},
  {"comic_detect", "{d}/good.png --json {d}/notes.txt/f.json", 1, {"notes.txt", "is not a folder"}},
  {"comic_detect", "{d}/good.png --overlay {d}/frames", 1, {"frames", "is a folder"}},
  {"comic_detect", "{d}/good.png --bogus", 2, {"--bogus"}},
  {"comic_detect", "{d}/good.png --scale abc", 2, {"--scale", "abc"}},
  {"comic_detect", "", 2, {"IMAGE"}},
  // Issue 29: outputs that are inputs (by device and inode, not by name) destroyed the image.
  {"comic_detect", "{d}/good.png --json {d}/good.png", 2, {"good.png", "--json is the input IMAGE"}},
  // Issue 29: an unknown overlay format failed after the work, in OpenCV's words.
  {"comic_detect", "{d}/good.png --overlay {d}/o.xyz", 2, {"o.xyz", "--overlay", "'xyz'"}},
  {"comic_inspect", "{e} --contact-sheet {d}/sheet.txt", 2, {"sheet.txt", "--contact-sheet"}},
  {"comic_detect", "{d}/good.png --overlay {d}/frames/../good.png", 2,
   {"--overlay is the input IMAGE"}},
  {"comic_detect", "{d}/good.png --overlay {d}/link.png", 2, {"link.png", "is the input IMAGE"}},
  {"comic_detect", "{d}/link.png --json {d}/good.png --overlay {d}/o.png", 2,
   {"--json is the input IMAGE"}},
  // Issue 29: a small PNG declaring 30000x30000 was decoded (937 MB) before --max-pixels held.
  {"comic_detect", "{d}/huge.png", 1, {"huge.png", "30000x30000", "--max-pixels"}},
  // Issue 29: UTF-8 names read as typed, not as \xNN escapes.
  {"comic_detect", "{d}/stra\xc3\x9f" "e_\xe5\xb8\xa7.png", 1,
   {"stra\xc3\x9f" "e_\xe5\xb8\xa7.png", "no such file"}},
  // comic_sfm
  {"comic_sfm", "{d}/missing --output {d}/out", 1, {"missing", "no such file"}},
  {"comic_sfm", "{d}/emptydir --output {d}/out", 2, {"emptydir", "no images"}},
  {"comic_sfm", "{d}/notes.txt --output {d}/out", 1, {"notes.txt", "cannot open as a video"}},
  {"comic_sfm", "{d}/garbage.mp4 --output {d}/out", 1, {"garbage.mp4", "cannot open as a video"}},
  {"comic_sfm", "{d}/truncated.avi --output {d}/out", 1,
   {"truncated.avi", "stops decoding after frame", "--allow-truncated"}},
  {"comic_sfm", "{d}/mismatched --output {d}/out", 1, {"b.png", "differs"}},
  {"comic_sfm", "{e} --gt {d}/poses_short.txt --output {d}/out", 1,
   {"poses_short.txt", "covers 3 of the 12 frames", "--gt-partial"}},
  {"comic_sfm", "{e} --gt {d}/garbage.txt --gt-format kitti --output {d}/out", 1, {"garbage.txt"}},
  {"comic_sfm", "{e} --gt {d}/missing.txt --output {d}/out", 1, {"missing.txt"}},
  {"comic_sfm", "{e} --gt {x}/poses.txt --gt-format bogus --output {d}/out", 2, {"bogus"}},
  {"comic_sfm", "{e} --intrinsics {d}/garbage.txt --output {d}/out", 1, {"garbage.txt"}},
  {"comic_sfm", "{e} --intrinsics {d}/missing.txt --output {d}/out", 1, {"missing.txt"}},
  {"comic_sfm", "{e} --intrinsics {d}/calib_k3.yml --output {d}/out", 1,
   {"calib_k3.yml", "k3", "not supported"}},
  {"comic_sfm", "{e} --intrinsics {d}/calib_nomatrix.yml --output {d}/out", 1,
   {"calib_nomatrix.yml", "camera_matrix"}},
  {"comic_sfm", "{e} --intrinsics {d}/calib_broken.yml --output {d}/out", 1,
   {"calib_broken.yml", "FileStorage"}},
  {"comic_sfm", "{e} --intrinsics {d}/fisheye_cameras.txt --output {d}/out", 1,
   {"fisheye_cameras.txt", "OPENCV_FISHEYE", "not supported"}},
  {"comic_sfm", "{e} --intrinsics {d}/short_cameras.txt --output {d}/out", 1,
   {"short_cameras.txt", "takes 4 parameters"}},
  {"comic_sfm", "{e} --intrinsics {d}/small_cameras.txt --output {d}/out", 1,
   {"small_cameras.txt", "calibration is for 640x480", "1226x370"}},
  {"comic_sfm", "{e} --intrinsics {d}/seven.txt --output {d}/out", 1, {"seven.txt", "got 7"}},
  {"comic_sfm", "{e} --camera-model FISHEYE --output {d}/out", 2, {"--camera-model", "FISHEYE"}},
  {"comic_sfm", "{e} --intrinsics {d}/two_focals.txt --camera-model SIMPLE_RADIAL --output {d}/out",
   2, {"--camera-model", "SIMPLE_RADIAL", "cannot hold"}},
  {"comic_sfm", "{e} --regions {d}/garbage.txt --output {d}/out", 1, {"garbage.txt"}},
  {"comic_sfm", "{e} --regions {d}/boxes_short.txt --output {d}/out", 1, {"boxes_short.txt"}},
  {"comic_sfm", "{e} --masks {d}/emptydir --output {d}/out", 2, {"emptydir", "holds no images"}},
  {"comic_sfm", "{e} --regions {d}/boxes_short.txt --masks {d}/emptydir --output {d}/out", 2,
   {"--regions", "--masks"}},
  {"comic_sfm", "{e} --output {d}/notes.txt", 1, {"notes.txt", "is not a folder"}},
  {"comic_sfm", "{e} --output {d}/notes.txt/sub", 1, {"notes.txt", "is not a folder"}},
  {"comic_sfm", "{e} --output {d}/out --colmap-db {d}/existing.db", 1,
   {"existing.db", "already exists"}},
  {"comic_sfm", "{e} --output {d}/out --colmap-db {d}/notes.txt/a.db", 1,
   {"notes.txt", "is not a folder"}},
  // The database fails only after the reconstruction: no model may be left in --out.
  {"comic_sfm", "{e} --output {d}/out --quiet --colmap-db /proc/tracks.db", 1, {"/proc/tracks.db"}},
  {"comic_sfm", "{e} --output {d}/out --overwrite", 2, {"--overwrite", "--colmap-db"}},
  {"comic_sfm", "{e} --output {d}/out --threads 100000", 2, {"--threads", "hardware"}},
  {"comic_sfm", "{e} --output {d}/out --resize-height 100000", 2, {"--resize-height", "100000"}},
  {"comic_sfm", "{e} --output {d}/out --resize-height 1", 2, {"--resize-height", "[8, 16384]"}},
  {"comic_sfm", "{e} --output {d}/out --detector bogus", 2, {"bogus"}},
  {"comic_sfm", "{e} --output {d}/out --stride 0", 2, {"stride"}},
  {"comic_sfm", "{e} --output {d}/out --first 100", 2, {"selects none"}},
  {"comic_sfm", "{e} --output {d}/out --max-pixels 1000", 1, {"000000.png", "--max-pixels"}},
  {"comic_sfm", "{e} --output {d}/out --plot-plane bogus", 2, {"--plot-plane", "bogus"}},
  {"comic_sfm", "{d}/thin --output {d}/out", 1,
   {"thin/000000.png", "2000x1 pixels (as stored) are too small to reconstruct"}},
  {"comic_sfm", "{e} --output {d}/out --global-ba-max-images 1", 2,
   {"--global-ba-max-images", ">= 2", "got 1"}},
  {"comic_sfm", "{e} --output {d}/out --colmap-threads 100000", 2, {"--colmap-threads"}},
  {"comic_sfm", "{e} --output {d}/out --write-frames", 2,
   {"--write-frames", "folder of images already"}},
  {"comic_sfm", "{e} --output {d}/out --write-frames=", 2, {"--write-frames", "needs a value"}},
  {"comic_sfm", "{e} --output {d}/out --write-frames {d}/frames", 2, {"unexpected argument"}},
  {"comic_sfm", "{d}/truncated.avi --output {d}/out --write-frames", 1, {"truncated.avi"}},
  {"comic_sfm", "{d}/garbage.mp4 --output {d}/out --colmap-db {d}/a.db", 1,
   {"garbage.mp4", "cannot open as a video"}},
  {"comic_sfm", "{e} --output {d}/out --matching foo", 2, {"--matching", "'foo'"}},
  {"comic_sfm", "{e} --output {d}/out --matching window:0", 2, {"--matching", "window:0"}},
  {"comic_sfm", "{e} --output {d}/out --matching window:x", 2, {"--matching", "window:x"}},
  {"comic_sfm", "{e} --output {d}/out --detector comic+bogus", 2, {"bogus", "comic+bogus"}},
  {"comic_sfm", "{e} --output {d}/out --detector harris+harris", 2, {"harris", "twice"}},
  {"comic_sfm", "{e} --output {d}/out --compare --detectors harris,hessian+bogus", 2,
   {"bogus", "hessian+bogus"}},
  // Issue 29: inputs are sacred; -o FRAMES wrote trajectory.png among the frames.
  {"comic_sfm", "{d}/frames --output {d}/frames", 2, {"--output is the input FRAMES"}},
  {"comic_sfm", "{d}/frames --output {d}/frames/out", 2, {"--output lies inside the input FRAMES"}},
  // Issue 26: the track cache is written too, never among the inputs nor in --output (replaced).
  {"comic_sfm", "{d}/frames --output {d}/out --cache {d}/frames", 2, {"--cache is the input FRAMES"}},
  {"comic_sfm", "{d}/frames --output {d}/out --cache {d}/frames/cache", 2,
   {"--cache lies inside the input FRAMES"}},
  {"comic_sfm", "{e} --output {d}/out --cache {d}/out/cache", 2,
   {"--cache", "lies inside, --output", "which each run replaces"}},
  {"comic_sfm", "{e} --output {d}/out --colmap-db {d}/poses_short.txt --overwrite --gt-partial "
   "--gt {d}/poses_short.txt", 2, {"--colmap-db is the input --gt"}},
  {"comic_sfm", "{e} --output {d}/out --intrinsics {d}/notes.txt --colmap-db {d}/notes.txt --overwrite",
   2, {"--colmap-db is the input --intrinsics"}},
  // Issue 29: calibration values out of any lens's range ran to 0 verified pairs (cx = 1e300) or
  // ended without the file's name (fx = 1e308: "USAC threshold must be > 0").
  {"comic_sfm", "{e} --intrinsics {d}/calib_cx.txt --output {d}/out", 1,
   {"calib_cx.txt", "principal point cx = 1e+300"}},
  {"comic_sfm", "{e} --intrinsics {d}/calib_huge.txt --output {d}/out", 1,
   {"calib_huge.txt", "focal length fx = 1e+308"}},
  {"comic_sfm", "{e} --intrinsics {d}/calib_k1.yml --output {d}/out", 1,
   {"calib_k1.yml", "distortion coefficient k1"}},
  // Issue 29: errors without the file, and cut at a NUL byte.
  {"comic_sfm", "{e} --intrinsics {d}/foo_cameras.txt --output {d}/out", 1,
   {"foo_cameras.txt:1", "FOO_MODEL", "not one of COLMAP's models"}},
  {"comic_sfm", "{e} --intrinsics {d}/nul.txt --output {d}/out", 1,
   {"nul.txt", "not a text file (a NUL byte at offset 3)"}},
  {"comic_sfm", "{e} --gt {d}/poses_nul.txt --output {d}/out", 1, {"poses_nul.txt", "\\x00"}},
  // Issue 29: a frame name with a space failed only after the whole reconstruction.
  {"comic_sfm", "{d}/spaced --output {d}/out", 1, {"spaced", "'img 000000.png'", "whitespace"}},
  // Issue 29: every frame's header against the budget and the first frame's size, before work.
  {"comic_sfm", "{d}/huge_second --output {d}/out", 1, {"huge.png", "30000x30000", "--max-pixels"}},
  {"comic_sfm", "{d}/onlyfifo --output {d}/out", 2, {"onlyfifo", "no images", "'x.png' (a FIFO)"}},
  // A COLMAP project as --output: every input at a path the run writes stays as it was.
  {"comic_sfm", "{e} --gt {d}/proj/sparse/0 --output {d}/proj", 2,
   {"proj/sparse/0: the input --gt would be replaced", "--output writes {d}/proj/sparse"}},
  {"comic_sfm", "{e} --intrinsics {d}/proj/cameras.txt --output {d}/proj", 2,
   {"proj/cameras.txt: the input --intrinsics would be replaced", "{d}/proj/cameras.txt"}},
  {"comic_sfm", "{d}/proj/sparse --output {d}/proj", 2,
   {"proj/sparse: the input FRAMES would be replaced", "--output writes {d}/proj/sparse"}},
  {"comic_sfm", "{e} --gt {d}/proj/images/../sparse/0/images.txt --output {d}/proj/", 2,
   {"the input --gt would be replaced", "--output writes {d}/proj/sparse"}},
  {"comic_sfm", "{e} --regions {d}/proj/report.json --output {d}/proj", 2,
   {"the input --regions would be replaced", "{d}/proj/report.json"}},
  {"comic_sfm", "{e} --masks {d}/proj/sparse/0 --output {d}/proj", 2,
   {"the input --masks would be replaced"}},
  {"comic_sfm", "{e} --gt {d}/proj/harris/report.json --output {d}/proj --compare --detectors harris",
   2, {"the input --gt would be replaced", "--output writes {d}/proj/harris"}},
  // FIFOs block open() until a writer comes: refused from stat, at once, as every input.
  {"comic_detect", "{d}/fifo.png", 1, {"fifo.png", "not a regular file (a FIFO)"}},
  {"comic_sfm", "{e} --intrinsics {d}/fifo.txt --output {d}/out", 1,
   {"fifo.txt", "not a regular file (a FIFO)"}},
  {"comic_sfm", "{e} --gt {d}/fifo.txt --output {d}/out", 1,
   {"fifo.txt", "not a regular file (a FIFO)"}},
  {"comic_sfm", "{e} --regions {d}/fifo.txt --output {d}/out", 1,
   {"fifo.txt", "not a regular file (a FIFO)"}},
  {"comic_sfm", "{d}/fifo.mp4 --output {d}/out", 1, {"fifo.mp4", "not a regular file (a FIFO)"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --intrinsics {d}/fifo.txt", 1,
   {"fifo.txt", "not a regular file (a FIFO)"}},
  {"comic_render", "{d}/fifo.json --photos {d}/good.png --output {d}/out", 1,
   {"fifo.json", "not a regular file (a FIFO)"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/fifo.png --output {d}/out",
   1, {"fifo.png", "not a regular file (a FIFO)"}},
  // comic_track_eval
  {"comic_track_eval", "{d}/missing --output {d}/out", 1, {"missing", "no such file"}},
  {"comic_track_eval", "{d}/truncated.avi --output {d}/out", 1, {"truncated.avi", "stops decoding"}},
  {"comic_track_eval", "{e} --regions {d}/garbage.txt --output {d}/out", 1, {"garbage.txt"}},
  {"comic_track_eval", "{e} --regions {d}/boxes_short.txt --output {d}/out", 1, {"boxes_short.txt"}},
  {"comic_track_eval", "{e} --regions {d}/boxes_short.txt --masks {d}/emptydir --output {d}/out", 2,
   {"--masks", "--regions"}},
  {"comic_track_eval", "{e} --poses {x}/poses.txt --output {d}/out", 2, {"--poses", "--calib"}},
  {"comic_track_eval", "{e} --poses {d}/poses_short.txt --calib {x}/calib.txt --output {d}/out", 1,
   {"poses_short.txt", "3 poses"}},
  {"comic_track_eval", "{e} --threads 100000 --output {d}/out", 2, {"--threads", "hardware"}},
  {"comic_track_eval", "{e} --output {d}/notes.txt", 1, {"notes.txt", "is not a folder"}},
  {"comic_track_eval", "{e} --n 0 --output {d}/out", 2, {"--n"}},
  {"comic_track_eval", "{e} --n 100 --output {d}/out", 2, {"--n 100", "frames"}},
  {"comic_track_eval", "{e} --detectors bogus --output {d}/out", 2, {"bogus"}},
  {"comic_track_eval", "{e} --resize-height 100000 --output {d}/out", 2, {"--resize-height"}},
  {"comic_track_eval", "{d}/frames --output {d}/frames/te", 2, {"--output lies inside the input FRAMES"}},
  {"comic_track_eval", "{e} --resize-height 1 --output {d}/out", 2, {"--resize-height", "got 1"}},
  // comic_stereo_eval
  {"comic_stereo_eval", "{d}/missing.png {d}/good.png --disparity {d}/good.png --disparity-scale 4 "
   "--output {d}/out", 1, {"missing.png"}},
  {"comic_stereo_eval", "{d}/good.png {d}/good.png --output {d}/out", 2, {"--disparity"}},
  {"comic_stereo_eval", "{d}/garbage.png {d}/good.png --disparity {d}/good.png --disparity-scale 4 "
   "--output {d}/out", 1, {"garbage.png", "cannot decode"}},
  {"comic_stereo_eval", "{d}/good.png {d}/good.png --disparity {d}/good.png --disparity-scale 4 "
   "--threads 100000 --output {d}/out", 2, {"--threads", "hardware"}},
  {"comic_stereo_eval", "{d}/good.png {d}/good.png --disparity {d}/good.png --disparity-scale 4 "
   "--resize-height 100000 --output {d}/out", 2, {"--resize-height", "100000"}},
  {"comic_stereo_eval", "--middlebury {d}/emptydir --output {d}/out", 1, {"emptydir"}},
  {"comic_stereo_eval", "--middlebury {d}/missing --output {d}/out", 1, {"missing"}},
  {"comic_stereo_eval", "{d}/good.png {d}/frames/000000.png --disparity {d}/good.png "
   "--disparity-scale 4 --output {d}/frames/000000.png", 2, {"--output is the input RIGHT"}},
  {"comic_stereo_eval", "{d}/good.png {d}/good.png --disparity {d}/good.png --disparity-scale 4 "
   "--resize-height 3 --output {d}/out", 2, {"--resize-height", "got 3"}},
  // comic_export_colmap
  {"comic_export_colmap", "{e}", 2, {"--colmap-db"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/existing.db", 1, {"existing.db", "already exists"}},
  {"comic_export_colmap", "{d}/missing --colmap-db {d}/a.db", 1, {"missing", "no such file"}},
  {"comic_export_colmap", "{d}/good.png --colmap-db {d}/a.db", 2, {"good.png", "not a folder"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --threads 100000", 2, {"--threads", "hardware"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --camera-model bogus", 2,
   {"--camera-model", "bogus"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --intrinsics {d}/calib_k3.yml", 1,
   {"calib_k3.yml", "k3"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --matching foo", 2, {"--matching", "'foo'"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --matching window:0", 2,
   {"--matching", "window:0"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --detector fast+bogus", 2,
   {"bogus", "fast+bogus"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --intrinsics {d}/garbage.txt", 1,
   {"garbage.txt"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/notes.txt/a.db", 1, {"notes.txt", "is not a folder"}},
  {"comic_export_colmap", "{d}/emptydir --colmap-db {d}/a.db", 2, {"emptydir", "no images"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --max-pixels 1000", 1, {"--max-pixels"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --write-frames", 2,
   {"--write-frames", "folder of images already"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --resize-height 100", 2,
   {"--resize-height", "video"}},
  {"comic_export_colmap", "{d}/truncated.avi --colmap-db {d}/a.db", 1,
   {"truncated.avi", "stops decoding"}},
  {"comic_export_colmap", "{d}/garbage.mp4 --colmap-db {d}/a.db", 1,
   {"garbage.mp4", "cannot open as a video"}},
  {"comic_export_colmap", "{d}/truncated.avi --colmap-db {d}/a.db --write-frames={d}/notes.txt",
   1, {"notes.txt", "is not a folder"}},
  // Issue 29: `--colmap-db frames/000000.png --overwrite` replaced a frame with the database.
  {"comic_export_colmap", "{d}/frames --colmap-db {d}/frames/000000.png --overwrite", 2,
   {"000000.png", "--colmap-db lies inside the input FRAMES"}},
  {"comic_export_colmap", "{e} --colmap-db {d}/a.db --intrinsics {d}/calib_cx.txt", 1,
   {"calib_cx.txt", "principal point cx"}},
  {"comic_export_colmap", "{d}/truncated.avi --colmap-db {d}/a.db --write-frames={d}/truncated.avi",
   2, {"--write-frames is the input FRAMES"}},
  // Issue 29: a journal left beside a database that is gone would be replayed into ours.
  {"comic_export_colmap", "{e} --colmap-db {d}/gone.db", 1,
   {"gone.db-journal", "a journal is left beside", "gone.db"}},
  {"comic_export_colmap", "{d}/truncated.avi --colmap-db {d}/proj/a.db --intrinsics "
   "{d}/proj/images/calib.txt", 2,
   {"calib.txt: the input --intrinsics would be replaced", "--colmap-db writes {d}/proj/images"}},
  {"comic_export_colmap", "{d}/truncated.avi --colmap-db {d}/a.db --write-frames={d}/proj "
   "--intrinsics {d}/proj/cameras.txt", 2,
   {"the input --intrinsics would be replaced", "--write-frames writes {d}/proj"}},
  // comic_inspect
  {"comic_inspect", "{d}/missing", 1, {"missing", "no such file"}},
  {"comic_inspect", "{d}/garbage.mp4", 1, {"garbage.mp4", "cannot open as a video"}},
  {"comic_inspect", "{d}/truncated.avi", 1, {"truncated.avi", "stops decoding", "frame"}},
  {"comic_inspect", "{d}/emptydir", 2, {"emptydir", "no images"}},
  {"comic_inspect", "{e} --contact-sheet {d}/notes.txt/s.png", 1, {"notes.txt", "not a folder"}},
  {"comic_inspect", "{e} --sheet-frames 0", 2, {"--sheet-frames"}},
  {"comic_inspect", "{e} --stride 0", 2, {"stride"}},
  {"comic_inspect", "{e} --resize-height 100000", 2, {"--resize-height"}},
  {"comic_inspect", "{e} --resize-height 7", 2, {"--resize-height", "got 7"}},
  {"comic_inspect", "{d}/truncated.png", 1, {"truncated.png", "truncated"}},
  {"comic_inspect", "{d}/frames --contact-sheet {d}/frames/000000.png", 2,
   {"--contact-sheet lies inside the input FRAMES"}},
  {"comic_inspect", "{d}/onlyfifo", 2, {"onlyfifo", "'x.png' (a FIFO)"}},
  {"comic_inspect", "{d}/huge_second", 1, {"huge.png", "30000x30000"}},
  // The decoder goes by content, not by name: the header of every format it reads is read before
  // decoding (a WebP named .png, a Radiance HDR, ...), and content of no such format is refused.
  {"comic_detect", "{d}/webp_huge.png", 1, {"webp_huge.png", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/huge.hdr", 1, {"huge.hdr", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/j2k_huge.jpg", 1, {"j2k_huge.jpg", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/jp2_huge.tif", 1, {"jp2_huge.tif", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/exr_huge.bmp", 1, {"exr_huge.bmp", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/ras_huge.pgm", 1, {"ras_huge.pgm", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/pam_huge.pnm", 1, {"pam_huge.pnm", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/pfm_huge.ppm", 1, {"pfm_huge.ppm", "12000x12000", "--max-pixels"}},
  {"comic_detect", "{d}/gif.png", 1, {"gif.png", "cannot decode image", "WebP, Radiance HDR"}},
  {"comic_sfm", "{d}/webp_second --output {d}/out", 1,
   {"webp_huge.png", "12000x12000", "--max-pixels"}},
  {"comic_inspect", "{d}/webp_second", 1, {"webp_huge.png", "12000x12000", "--max-pixels"}},
  {"comic_sfm", "{d}/gif_second --output {d}/out", 1, {"gif.png", "cannot decode image"}},
  // comic_render ({x}/../../../scenes is the repository's scenes/)
  {"comic_render", "{d}/missing.json --photos {d}/good.png --output {d}/out", 1,
   {"missing.json", "no such scene file"}},
  {"comic_render", "{d}/notes.txt --photos {d}/good.png --output {d}/out", 1,
   {"notes.txt", "not valid JSON"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/garbage.png --output {d}/out",
   1, {"garbage.png", "cannot decode"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/emptydir --output {d}/out", 2,
   {"--photos", "no images"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --output {d}/out", 2, {"--photos"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/good.png --output {d}/notes.txt",
   1, {"notes.txt", "not a folder"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/good.png --depth-format exr "
   "--output {d}/out", 2, {"depth format", "exr"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/good.png --shutter 3 "
   "--output {d}/out", 2, {"shutter"}},
  // A scene's values bound the work before any, in the scene's words (key, limits, value).
  {"comic_render", "{d}/scene_tile.json --photos {d}/good.png --output {d}/out", 2,
   {"scene_tile.json", "\"tile\": must be in [0.1, 1000], got 0"}},
  {"comic_render", "{d}/scene_segments.json --photos {d}/good.png --output {d}/out", 2,
   {"\"segments\": must be in [3, 4096], got 1e+09"}},
  {"comic_render", "{d}/scene_gap.json --photos {d}/good.png --output {d}/out", 2,
   {"\"gap\": must be in [0, 1000], got -5"}},
  {"comic_render", "{d}/scene_spacing.json --photos {d}/good.png --output {d}/out", 2,
   {"\"spacing\": must be in [0.1, 10000], got 1e-06"}},
  {"comic_render", "{d}/scene_width.json --photos {d}/good.png --output {d}/out", 2,
   {"\"width\": expected a whole number within int's range, got 4294967297"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/good.png --stereo-pairs "
   "2147483647 --output {d}/out", 2, {"--stereo-pairs must be in [0, 100000], got 2147483647"}},
  {"comic_render", "{d}/scene_big.json --photos {d}/good.png --output {d}/out", 1,
   {"scene_big.json", "16384x16384 = 268435456 pixels per frame", "--max-pixels 268435456"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/good.png --max-pixels 0 "
   "--output {d}/out", 2, {"--max-pixels"}},
  {"comic_render", "{d}/scene_deep.json --photos {d}/good.png --output {d}/out", 1,
   {"scene_deep.json", "nested deeper than 64 levels"}},
  // A scene reads files beside it only, never any file a path names (and quotes in an error).
  {"comic_render", "{d}/scene_poses.json --photos {d}/good.png --output {d}/out", 2,
   {"\"file\"", "inside the scene's folder", "../../../../etc/passwd"}},
  // comic_render: outputs never among the inputs, nor inputs where the render writes
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/frames --output {d}/frames",
   2, {"--output is the input --photos"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/frames --output "
   "{d}/frames/render", 2, {"lies inside the input --photos"}},
  {"comic_render", "{x}/../../../scenes/test_street.json --photos {d}/good.png --output {d}", 2,
   {"holds the input --photos"}},
  // comic_render_eval
  {"comic_render_eval", "{d}/missing --output {d}/out", 1, {"missing", "no such folder"}},
  {"comic_render_eval", "{d}/frames --output {d}/out", 1, {"frames", "--frames-only"}},
  {"comic_render_eval", "{d}/notes.txt --output {d}/out", 1, {"notes.txt", "no such folder"}},
  {"comic_render_eval", "{d}/frames --detectors sift --output {d}/out", 2, {"sift"}},
  {"comic_render_eval", "{d}/frames --boundary-band -1 --output {d}/out", 2, {"boundary band"}},
  {"comic_render_eval", "{d}/frames --output {d}/notes.txt", 1, {"notes.txt", "not a folder"}},
  {"comic_render_eval", "{d}/frames --output {d}/frames", 2, {"--output is the input RENDERED"}},
  {"comic_render_eval", "{d}/frames --output {d}/frames/eval", 2,
   {"lies inside the input RENDERED"}},
  // comic_track_survival (prints its tables; writes nothing)
  {"comic_track_survival", "{d}/missing", 1, {"missing", "no such file"}},
  {"comic_track_survival", "{d}/notes.txt", 1, {"notes.txt", "cannot open"}},
  {"comic_track_survival", "{d}/frames --horizon -1", 2, {"--horizon"}},
  // comic_bench
  {"comic_bench", "{d}/missing.png", 1, {"missing.png", "no such file"}},
  {"comic_bench", "{d}/garbage.png", 1, {"garbage.png", "cannot decode"}},
  {"comic_bench", "{d}/good.png --threads 100000", 2, {"--threads", "hardware"}},
  {"comic_bench", "{d}/good.png --runs 0", 2, {"--runs"}},
  {"comic_bench", "{d}/good.png --json {d}/notes.txt/b.json", 1, {"notes.txt", "not a folder"}},
  {"comic_bench", "{d}/good.png --match-only", 2, {"--match-only", "--match-pair"}},
  {"comic_bench", "{d}/good.png --match-pair {d}/missing.png --match-only", 1,
   {"missing.png", "no such file"}},
  {"comic_bench", "{d}/mismatched/a.png --match-pair {d}/mismatched/b.png", 2,
   {"b.png", "equal sizes"}},
  {"comic_bench", "{d}/good.png --keep 1000", 2, {"--keep", "--perturbations"}},
  {"comic_bench", "{d}/good.png --json {d}/good.png", 2, {"--json is the input IMAGE"}},
  {"comic_bench", "{d}/good.png --resize-height 2", 2, {"--resize-height", "got 2"}},
  // Smaller things. FFmpeg decodes in threads of its own: the damage of a frame decoded ahead is
  // reported after the call that started it returned, and must still not reach stderr.
  {"comic_sfm", "{d}/damaged.mp4 --output {d}/out", 1, {"damaged.mp4", "stops decoding"}},
  {"comic_track_eval", "{d}/damaged.mp4 --output {d}/out", 1, {"damaged.mp4", "stops decoding"}},
  {"comic_export_colmap", "{d}/damaged.mp4 --colmap-db {d}/a.db", 1,
   {"damaged.mp4", "stops decoding"}},
  {"comic_inspect", "{d}/damaged.mp4", 1, {"damaged.mp4", "stops decoding"}},
  // A tab or a line break in a name is escaped as \xNN, never shown as a space.
  {"comic_detect", "'{d}/tab\tname.png'", 1, {"{d}/tab\\x09name.png: no such file"}},
  {"comic_detect", "'{d}/line\nname.png'", 1, {"{d}/line\\x0aname.png: no such file"}},
  {"comic_sfm", "'{d}/cr\rframes' --output {d}/out", 1, {"{d}/cr\\x0dframes", "no such file"}},
  // Frames too small for a detector's window, in every app that tracks them.
  {"comic_track_eval", "{d}/thin --output {d}/out", 1, {"thin/000000.png", "2000x1"}},
  {"comic_export_colmap", "{d}/thin --colmap-db {d}/a.db", 1, {"thin/000000.png", "2000x1"}},
  {"comic_sfm", "{d}/tall --output {d}/out", 1, {"tall/000000.png", "1x2000"}},
  // Out of memory: one line naming the image, with what to do (a PNG whose pixels, 900 MB as
  // declared, are allowed by --max-pixels, run under a 700 MB address-space limit).
  {"comic_detect", "{d}/oom.png --max-pixels 1000000000 --threads 1", 1,
   {"oom.png: out of memory for its 30000x30000 pixels", "--max-pixels"}, 700},
  // A rendered truth whose depth map has another size than its frames: refused before tracking.
  {"comic_render_eval", "{d}/rendered --output {d}/out", 1,
   {"rendered/depth/000001.pfm: 80x60, but the frames are 160x120"}},
};
// clang-format on

std::string SceneDir() { return comic::test::SourceDir() + "/scenes"; }

std::string Substitute(std::string text, const std::string& dir) {
  const std::vector<std::pair<std::string, std::string>> keys = {
      {"{d}", dir}, {"{e}", ExampleDir() + "/image_l"}, {"{x}", ExampleDir()}};
  for (const auto& [key, value] : keys) {
    for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
      text.replace(at, key.size(), value);
      at += value.size();
    }
  }
  return text;
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string RandomBytes(size_t n, uint32_t seed) {
  std::mt19937 random(seed);
  std::string bytes(n, '\0');
  for (char& c : bytes) c = static_cast<char>(random() & 0xff);
  return bytes;
}

// A textured frame, so that the detectors find something on it.
cv::Mat TexturedFrame(int width, int height, int shift) {
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(60, 60, 60));
  for (int k = 0; k < 12; ++k) {
    const cv::Point corner(20 + (k * 37) % (width - 60) + shift, 15 + (k * 53) % (height - 50));
    cv::rectangle(image, corner, corner + cv::Point(25, 20), cv::Scalar::all(120 + 10 * k), -1);
  }
  return image;
}

// The first 33 bytes of a PNG (signature and IHDR) declaring `width` x `height`, 8-bit grey.
std::string PngHeader(uint32_t width, uint32_t height) {
  const auto big_endian = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  return std::string("\x89PNG\r\n\x1a\n", 8) + big_endian(13) + "IHDR" + big_endian(width) +
         big_endian(height) + std::string("\x08\x00\x00\x00\x00", 5) + big_endian(0);
}

// Issue 29's inputs: a symlink to an input, a small file declaring a huge image, calibrations
// out of any lens's range, a NUL byte in numbers, a frame name with spaces, a FIFO named as a
// frame, a journal whose database is gone.
void MakeIssue29Fixture(const std::string& dir) {
  const std::string example = ExampleDir() + "/image_l/";
  fs::create_symlink(dir + "/good.png", dir + "/link.png");
  WriteBytes(dir + "/huge.png", PngHeader(30000, 30000) + std::string(2000, '\0'));
  WriteBytes(dir + "/calib_cx.txt", "700 700 1e300 185\n");
  WriteBytes(dir + "/calib_huge.txt", "1e308 1e308 613 185\n");
  WriteBytes(dir + "/calib_k1.yml",
             "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
             "   data: [ 707., 0., 601., 0., 707., 183., 0., 0., 1. ]\n"
             "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 4\n   dt: d\n"
             "   data: [ 1e6, 0.1, 0.001, -0.002 ]\n");
  WriteBytes(dir + "/foo_cameras.txt", "1 FOO_MODEL 1226 370 700 613 185\n");
  WriteBytes(dir + "/nul.txt", std::string("700\0x 700 613 185\n", 18));
  std::string poses = ReadBytes(ExampleDir() + "/poses.txt");
  poses.insert(poses.find(' ', poses.find('\n')), std::string("\0", 1));  // in line 2
  WriteBytes(dir + "/poses_nul.txt", poses);
  fs::create_directories(dir + "/spaced");
  fs::copy_file(example + "000000.png", dir + "/spaced/img 000000.png");
  fs::copy_file(example + "000001.png", dir + "/spaced/img 000001.png");
  fs::create_directories(dir + "/huge_second");
  fs::copy_file(example + "000000.png", dir + "/huge_second/000000.png");
  fs::copy_file(dir + "/huge.png", dir + "/huge_second/huge.png");
  fs::create_directories(dir + "/onlyfifo");
  ASSERT_EQ(::mkfifo((dir + "/onlyfifo/x.png").c_str(), 0644), 0);
  WriteBytes(dir + "/gone.db-journal", std::string(600, 'j'));
}

std::string LittleEndian32(uint32_t v) {
  return std::string{static_cast<char>(v), static_cast<char>(v >> 8), static_cast<char>(v >> 16),
                     static_cast<char>(v >> 24)};
}
std::string BigEndian32(uint32_t v) {
  return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                     static_cast<char>(v >> 8), static_cast<char>(v)};
}

// Headers of the other formats OpenCV decodes, each declaring 12000x12000 in under 100 bytes,
// under the names of formats the frame filter accepts; a GIF (no decoder, no header reader).
void MakeHeaderFixture(const std::string& dir) {
  const uint32_t n = 12000;
  const std::string exr_window =
      LittleEndian32(0) + LittleEndian32(0) + LittleEndian32(n - 1) + LittleEndian32(n - 1);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"webp_huge.png", "RIFF" + LittleEndian32(100) + "WEBPVP8L" + LittleEndian32(80) + "\x2f" +
                            LittleEndian32((n - 1) | (n - 1) << 14) + std::string(20, '\0')},
      {"huge.hdr",
       "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 12000 +X 12000\n" + std::string(16, '\0')},
      {"j2k_huge.jpg", std::string("\xff\x4f\xff\x51\x00\x29\x00\x00", 8) + BigEndian32(n) +
                           BigEndian32(n) + std::string(24, '\0')},
      {"jp2_huge.tif", std::string("\0\0\0\x0cjP  \r\n\x87\n", 12) + BigEndian32(45) + "jp2h" +
                           BigEndian32(22) + "ihdr" + BigEndian32(n) + BigEndian32(n) +
                           std::string(6, '\0')},
      {"exr_huge.bmp", "\x76\x2f\x31\x01" + LittleEndian32(2) + "dataWindow" + '\0' + "box2i" +
                           '\0' + LittleEndian32(16) + exr_window + '\0'},
      {"ras_huge.pgm", "\x59\xa6\x6a\x95" + BigEndian32(n) + BigEndian32(n) + BigEndian32(8) +
                           std::string(16, '\0')},
      {"pam_huge.pnm", "P7\nWIDTH 12000\nHEIGHT 12000\nDEPTH 1\nMAXVAL 255\nENDHDR\n"},
      {"pfm_huge.ppm", "PF\n12000 12000\n-1.0\n"},
      {"gif.png", std::string("GIF89a\x10\0\x10\0\0\0\0", 13) + std::string(40, '\0')}};
  for (const auto& [name, bytes] : files) WriteBytes(dir + "/" + name, bytes);
  const std::string example = ExampleDir() + "/image_l/000000.png";
  for (const std::string second : {"webp", "gif"}) {
    fs::create_directories(dir + "/" + second + "_second");
    fs::copy_file(example, dir + "/" + second + "_second/000000.png");
  }
  fs::copy_file(dir + "/webp_huge.png", dir + "/webp_second/webp_huge.png");
  fs::copy_file(dir + "/gif.png", dir + "/gif_second/gif.png");
}

// A COLMAP project (proj/sparse/0, proj/images) holding inputs where a run given --output proj
// writes: a model, a calibration, a report, a --compare detector's folder.
void MakeProjectFixture(const std::string& dir) {
  const std::string proj = dir + "/proj";
  fs::create_directories(proj + "/sparse/0");
  fs::create_directories(proj + "/images");
  fs::create_directories(proj + "/harris");
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt"}) {
    WriteBytes(proj + "/sparse/0/" + name, std::string("# ground truth ") + name + "\n");
  }
  fs::copy_file(ExampleDir() + "/image_l/000000.png", proj + "/images/000000.png");
  WriteBytes(proj + "/cameras.txt", "# calibration\n1 PINHOLE 1226 370 700 700 613 185\n");
  WriteBytes(proj + "/images/calib.txt", "700 700 613 185\n");
  WriteBytes(proj + "/report.json", "{\"an\": \"input\"}\n");
  WriteBytes(proj + "/harris/report.json", "{\"an\": \"input\"}\n");
}

// Scenes that asked for unbounded work, crashed the renderer or named a file outside their folder:
// test_street.json with one value changed.
void MakeSceneFixture(const std::string& dir) {
  const nlohmann::json street = nlohmann::json::parse(ReadBytes(SceneDir() + "/test_street.json"));
  const auto write = [&](const std::string& name,
                         const std::function<void(nlohmann::json*)>& edit) {
    nlohmann::json scene = street;
    edit(&scene);
    WriteBytes(dir + "/" + name, scene.dump());
  };
  write("scene_poses.json", [](nlohmann::json* s) {
    (*s)["path"] = {{"type", "poses"}, {"file", "../../../../etc/passwd"}};
  });
  write("scene_tile.json", [](nlohmann::json* s) { (*s)["elements"][0]["tile"] = 0; });
  write("scene_segments.json",
        [](nlohmann::json* s) { (*s)["elements"][1]["segments"] = 1000000000; });
  write("scene_gap.json", [](nlohmann::json* s) { (*s)["elements"][2]["gap"] = -5; });
  write("scene_spacing.json", [](nlohmann::json* s) { (*s)["elements"][3]["spacing"] = 1e-6; });
  write("scene_big.json", [](nlohmann::json* s) {
    (*s)["camera"] = {{"width", 16384}, {"height", 16384}};
  });
  write("scene_width.json", [](nlohmann::json* s) { (*s)["camera"]["width"] = 4294967297ull; });
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  WriteBytes(dir + "/scene_deep.json", "{\"description\": " + deep + "}");
}

// PNG's chunk checksum (CRC-32, ISO 3309), which libpng checks on the critical chunks.
uint32_t PngCrc(const std::string& bytes) {
  uint32_t crc = 0xffffffffu;
  for (const char c : bytes) {
    crc ^= static_cast<unsigned char>(c);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// Smaller things: an MPEG-4 video damaged in its middle (FFmpeg's decoder threads report it), a
// frame 1 pixel wide, a PNG whose header libpng accepts declaring 30000x30000 (its image data
// starts but is cut: the decoder allocates the pixels before it reads them), and a rendered truth
// (comic_render's output) with a depth map of the wrong size.
void MakeSmallerFixture(const std::string& dir) {
  const auto chunk = [](const std::string& type, const std::string& data) {
    return BigEndian32(static_cast<uint32_t>(data.size())) + type + data +
           BigEndian32(PngCrc(type + data));
  };
  const std::string ihdr =
      BigEndian32(30000) + BigEndian32(30000) + std::string("\x08\x00\x00\x00\x00", 5);
  WriteBytes(dir + "/oom.png", std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) +
                                   chunk("IDAT", std::string("\x78\x9c", 2)));
  const std::string video = dir + "/damaged_full.mp4";
  {
    cv::VideoWriter writer(video, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 10,
                           cv::Size(320, 240));
    ASSERT_TRUE(writer.isOpened());
    cv::RNG rng(1);
    cv::Mat noise(240, 320, CV_8UC3);
    for (int k = 0; k < 20; ++k) {
      rng.fill(noise, cv::RNG::UNIFORM, 0, 64);
      writer.write(TexturedFrame(320, 240, k) + noise);
    }
  }
  std::string bytes = ReadBytes(video);
  fs::remove(video);
  std::mt19937 random(1);
  for (int k = 0; k < 200; ++k) {
    bytes[bytes.size() / 5 + random() % (bytes.size() * 3 / 5)] = static_cast<char>(random());
  }
  WriteBytes(dir + "/damaged.mp4", bytes);
  fs::create_directories(dir + "/tall");
  for (const char* name : {"/tall/000000.png", "/tall/000001.png"}) {
    cv::imwrite(dir + name, cv::Mat(2000, 1, CV_8UC1, cv::Scalar(128)));
  }
  const std::string rendered = dir + "/rendered";
  for (const char* part : {"images", "depth", "boundaries", "colmap"}) {
    fs::create_directories(rendered + "/" + part);
  }
  for (const char* name : {"000000", "000001"}) {
    cv::imwrite(rendered + "/images/" + name + ".png", TexturedFrame(160, 120, 0));
    cv::imwrite(rendered + "/boundaries/" + name + ".png", cv::Mat(120, 160, CV_8UC1, 0.0));
  }
  cv::imwrite(rendered + "/depth/000000.pfm", cv::Mat(120, 160, CV_32FC1, 5.0));
  cv::imwrite(rendered + "/depth/000001.pfm", cv::Mat(60, 80, CV_32FC1, 5.0));
  WriteBytes(rendered + "/colmap/cameras.txt", "1 PINHOLE 160 120 100 100 80 60\n");
  WriteBytes(rendered + "/poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0.1 0 1 0 0 0 0 1 0\n");
}

// The fixture: every bad input the rows refer to, in one folder.
void MakeFixture(const std::string& dir) {
  const std::string good = ExampleDir() + "/image_l/000000.png";
  fs::copy_file(good, dir + "/good.png");
  fs::create_directories(dir + "/frames");
  fs::copy_file(good, dir + "/frames/000000.png");
  fs::create_directories(dir + "/emptydir");
  WriteBytes(dir + "/empty.png", "");
  WriteBytes(dir + "/garbage.png", RandomBytes(3000, 1));
  WriteBytes(dir + "/garbage.mp4", RandomBytes(5000, 2));
  // Binary garbage with line breaks and escape sequences: must never reach the terminal raw.
  WriteBytes(dir + "/garbage.txt", "\x1b[31m\x01\x02 1 2 3\n" + RandomBytes(500, 3));
  WriteBytes(dir + "/notes.txt", "not a folder\n");
  // Calibration files the camera models cannot hold or that are malformed (issue 17).
  WriteBytes(dir + "/calib_k3.yml",
             "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
             "   data: [ 707., 0., 601., 0., 707., 183., 0., 0., 1. ]\n"
             "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
             "   data: [ -0.3, 0.1, 0.001, -0.002, 0.05 ]\n");
  WriteBytes(dir + "/calib_nomatrix.yml", "%YAML:1.0\n---\nimage_width: 1226\n");
  WriteBytes(dir + "/calib_broken.yml", "%YAML:1.0\n---\ncamera_matrix: [1, 2\n  : :\n");
  WriteBytes(dir + "/fisheye_cameras.txt", "1 OPENCV_FISHEYE 1226 370 700 700 613 185 0 0 0 0\n");
  WriteBytes(dir + "/short_cameras.txt", "1 PINHOLE 1226 370 700 700 613\n");
  WriteBytes(dir + "/small_cameras.txt", "1 PINHOLE 640 480 500 500 320 240\n");
  WriteBytes(dir + "/seven.txt", "700 700 613 185 0.1 0.2 0.3\n");
  WriteBytes(dir + "/two_focals.txt", "700 710 613 185\n");
  WriteBytes(dir + "/existing.db", "an existing database\n");
  const std::string png = ReadBytes(good);
  WriteBytes(dir + "/truncated.png", png.substr(0, png.size() / 2));
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", cv::imread(good), jpeg);
  WriteBytes(dir + "/truncated.jpg",
             std::string(reinterpret_cast<const char*>(jpeg.data()), jpeg.size() / 2));
  fs::create_directories(dir + "/mismatched");
  cv::imwrite(dir + "/mismatched/a.png", TexturedFrame(320, 240, 0));
  cv::imwrite(dir + "/mismatched/b.png", TexturedFrame(300, 240, 0));
  // Ground truth for 3 of the example's 12 frames, and 2 boxes.
  const std::string poses = ReadBytes(ExampleDir() + "/poses.txt");
  size_t third_line = 0;
  for (int k = 0; k < 3; ++k) third_line = poses.find('\n', third_line) + 1;
  WriteBytes(dir + "/poses_short.txt", poses.substr(0, third_line));
  WriteBytes(dir + "/boxes_short.txt", "10,10,50,40\n12,10,50,40\n");
  // An MJPEG video of 20 frames, cut after 60 % of its bytes.
  const std::string video = dir + "/video_full.avi";
  {
    cv::VideoWriter writer(video, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
                           cv::Size(320, 240));
    ASSERT_TRUE(writer.isOpened());
    for (int k = 0; k < 20; ++k) writer.write(TexturedFrame(320, 240, k));
  }
  const std::string bytes = ReadBytes(video);
  WriteBytes(dir + "/truncated.avi", bytes.substr(0, bytes.size() * 6 / 10));
  fs::remove(video);
  MakeIssue29Fixture(dir);
  MakeHeaderFixture(dir);
  MakeProjectFixture(dir);
  MakeSceneFixture(dir);
  MakeSmallerFixture(dir);
  fs::create_directories(dir + "/thin");
  for (const char* name : {"/thin/000000.png", "/thin/000001.png"}) {
    cv::imwrite(dir + name, cv::Mat(1, 2000, CV_8UC1, cv::Scalar(128)));
  }
  for (const char* name : {"fifo.png", "fifo.txt", "fifo.mp4", "fifo.json"}) {
    ASSERT_EQ(::mkfifo((dir + "/" + name).c_str(), 0644), 0);
  }
}

uint64_t Fnv1a(const std::string& bytes) {
  uint64_t hash = 1469598103934665603ull;
  for (const char c : bytes) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return hash;
}

// Every entry below `dir` (hidden ones too): size and FNV-1a checksum of files, -1 for folders,
// -2 and the target's checksum for symlinks, -3 for other entries (a FIFO is never opened).
std::map<std::string, std::pair<int64_t, uint64_t>> Snapshot(const std::string& dir) {
  std::map<std::string, std::pair<int64_t, uint64_t>> entries;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    // Lexically: fs::relative() would resolve a symlink to its target's name.
    const std::string name = entry.path().lexically_relative(dir).string();
    const fs::file_status status = entry.symlink_status();
    if (fs::is_symlink(status)) {
      entries[name] = {-2, Fnv1a(fs::read_symlink(entry.path()).string())};
      continue;
    }
    if (fs::is_directory(status)) {
      entries[name] = {-1, 0};
      continue;
    }
    if (!fs::is_regular_file(status)) {
      entries[name] = {-3, 0};
      continue;
    }
    entries[name] = {static_cast<int64_t>(entry.file_size()),
                     Fnv1a(ReadBytes(entry.path().string()))};
  }
  return entries;
}

// Printable ASCII and well-formed UTF-8 (issue 29: a user's UTF-8 path is shown as typed), no
// control bytes but the final line break.
bool IsPrintableText(const std::string& text) {
  for (size_t at = 0; at < text.size();) {
    const unsigned char byte = static_cast<unsigned char>(text[at]);
    if (byte < 0x80) {
      if ((byte < 0x20 && byte != '\n') || byte == 0x7f) return false;
      ++at;
      continue;
    }
    const size_t length = byte >= 0xf0 ? 4 : byte >= 0xe0 ? 3 : byte >= 0xc2 ? 2 : 0;
    if (length == 0 || at + length > text.size()) return false;
    for (size_t k = 1; k < length; ++k) {
      if ((static_cast<unsigned char>(text[at + k]) & 0xc0) != 0x80) return false;
    }
    at += length;
  }
  return true;
}

class BadInputMatrix : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fixture_ = new ScopedTempDir();
    captures_ = new ScopedTempDir();
    MakeFixture(fixture_->path());
  }
  static void TearDownTestSuite() {
    delete fixture_;
    delete captures_;
  }
  static ScopedTempDir* fixture_;
  static ScopedTempDir* captures_;
};
ScopedTempDir* BadInputMatrix::fixture_ = nullptr;
ScopedTempDir* BadInputMatrix::captures_ = nullptr;

TEST_F(BadInputMatrix, EveryRowFailsWithOneLineOfOursAndLeavesTheFilesAsTheyWere) {
  ASSERT_GE(kCases.size(), 60u);
  std::set<std::string> apps;
  const std::string dir = fixture_->path();
  const std::string out_file = captures_->File("stdout");
  const std::string err_file = captures_->File("stderr");
  for (const Case& row : kCases) {
    apps.insert(row.app);
    const std::string args = Substitute(row.args, dir);
    SCOPED_TRACE(std::string(row.app) + " " + args);
    const auto before = Snapshot(dir);
    // A row that hangs (a FIFO opened) ends after the timeout with 124, a failure, not a hang.
    const std::string limit = row.memory_limit_mb > 0
                                  ? "ulimit -v " + std::to_string(row.memory_limit_mb * 1024) + "; "
                                  : "";
    const int status = std::system((limit + "timeout -k 5 " + std::to_string(kRowTimeoutSeconds) +
                                    " " + AppPath(row.app) + " " + args + " >" + out_file + " 2>" +
                                    err_file + " </dev/null")
                                       .c_str());
    ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal";
    ASSERT_NE(WEXITSTATUS(status), 124) << "hung: still running after the timeout";
    EXPECT_EQ(WEXITSTATUS(status), row.exit_code);
    const std::string err = ReadBytes(err_file);
    EXPECT_EQ(CountLines(err), 1) << err;
    EXPECT_TRUE(IsPrintableText(err)) << err;
    EXPECT_EQ(err.rfind(std::string(row.app) + ": error: ", 0), 0u) << err;
    for (const char* word : row.words) {
      EXPECT_NE(err.find(Substitute(word, dir)), std::string::npos)
          << "'" << word << "' missing in: " << err;
    }
    EXPECT_EQ(err.find(".tmp"), std::string::npos) << "names a temp file: " << err;
    EXPECT_EQ(err.find(".staging"), std::string::npos) << "names a temp folder: " << err;
    EXPECT_EQ(Snapshot(dir), before) << "the fixture folder changed";
  }
  // Every app (apps/*.cc) has rows.
  size_t num_apps = 0;
  for (const auto& entry : fs::directory_iterator(comic::test::SourceDir() + "/apps")) {
    num_apps += entry.path().extension() == ".cc";
  }
  EXPECT_EQ(apps.size(), num_apps);
}

// --allow-truncated turns the truncated video into a warning line and the frames used.
TEST_F(BadInputMatrix, AllowTruncatedWarnsAndUsesTheFramesBeforeTheBreak) {
  const std::string dir = fixture_->path();
  const std::string err_file = captures_->File("stderr_truncated");
  const std::string out_file = captures_->File("stdout_truncated");
  const int status =
      std::system((AppPath("comic_inspect") + " " + dir + "/truncated.avi --allow-truncated >" +
                   out_file + " 2>" + err_file)
                      .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const std::string err = ReadBytes(err_file);
  EXPECT_EQ(CountLines(err), 1) << err;
  EXPECT_NE(err.find("comic_inspect: warning: "), std::string::npos) << err;
  EXPECT_NE(err.find("using its first"), std::string::npos) << err;
  const std::string out = ReadBytes(out_file);
  const size_t at = out.find("frames:");
  ASSERT_NE(at, std::string::npos) << out;
  const int frames = std::stoi(out.substr(at + 7));
  EXPECT_GE(frames, 1);
  EXPECT_LT(frames, 20);
  EXPECT_NE(err.find("first " + std::to_string(frames) + " frames"), std::string::npos) << err;
}

// The cache is optional: what goes wrong with it is one warning line and a run that succeeds.
// Each case on five frames with Harris, the cache made by the first run.
TEST_F(BadInputMatrix, CacheEdgesWarnAndTheRunSucceeds) {
  ScopedTempDir dir;
  const std::string cache = dir.File("cache");
  const std::string out_file = captures_->File("stdout_cache");
  const std::string err_file = captures_->File("stderr_cache");
  int run = 0;
  const auto comic_sfm = [&]() -> int {
    const std::string command = "timeout -k 5 " + std::to_string(kRowTimeoutSeconds) + " " +
                                AppPath("comic_sfm") + " " + ExampleDir() +
                                "/image_l --last 4 --detector harris --cache " + cache +
                                " --output " + dir.File("out" + std::to_string(run++)) + " >" +
                                out_file + " 2>" + err_file + " </dev/null";
    const int status = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(status)) << "killed by a signal";
    return WEXITSTATUS(status);
  };
  ASSERT_EQ(comic_sfm(), 0) << ReadBytes(err_file);
  ASSERT_EQ(ReadBytes(err_file), "");
  const std::string file = fs::directory_iterator(cache)->path().string();
  const std::string good = ReadBytes(file);
  const auto expect_warning = [&](const std::vector<std::string>& words) {
    EXPECT_EQ(comic_sfm(), 0);
    const std::string err = ReadBytes(err_file);
    EXPECT_EQ(CountLines(err), 1) << err;
    EXPECT_EQ(err.rfind("comic_sfm: warning: ", 0), 0u) << err;
    for (const std::string& word : words) {
      EXPECT_NE(err.find(word), std::string::npos) << "'" << word << "' missing in: " << err;
    }
    EXPECT_TRUE(fs::exists(dir.File("out" + std::to_string(run - 1) + "/report.json")));
  };

  // A NaN position behind a valid checksum. Layout (frontend/matching/track_file.h): a 24-byte
  // header, the detector name, the image size, the frame names, the frame count, frame 0's
  // feature count, then its first feature's x.
  std::string forged = good;
  size_t x_at = 24 + 8 + std::string("harris").size() + 8 + 8 + 8 + 8;
  for (int k = 0; k < 5; ++k) x_at += 8 + std::string("000000.png").size();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(forged.data() + x_at, &nan, sizeof(nan));
  uint64_t checksum = 14695981039346656037ull;  // FNV-1a 64 of every byte before the checksum
  for (size_t k = 0; k + 8 < forged.size(); ++k) {
    checksum = (checksum ^ static_cast<unsigned char>(forged[k])) * 1099511628211ull;
  }
  std::memcpy(forged.data() + forged.size() - 8, &checksum, sizeof(checksum));
  WriteBytes(file, forged);
  expect_warning({file, "feature position nan", "detecting and tracking again"});
  EXPECT_EQ(ReadBytes(file), good);  // replaced by the tracks computed again

  // A link to /dev/zero in the file's place: not read, replaced.
  fs::remove(file);
  fs::create_symlink("/dev/zero", file);
  expect_warning({file, "not a regular file", "detecting and tracking again"});
  EXPECT_FALSE(fs::is_symlink(fs::symlink_status(file)));
  EXPECT_EQ(ReadBytes(file), good);

  // The file cannot be written (a folder holds its name): the run goes on without it.
  fs::remove(file);
  fs::create_directories(file + "/x");
  expect_warning({file, "the tracks are not kept in --cache, the run goes on"});
  fs::remove_all(file);

  // A write failing on a full disk, leaving no empty folder: tests/sfm/run/track_cache_test.cc.

  // A read-only cache folder holding the right file: read, no warning.
  WriteBytes(file, good);
  fs::permissions(cache, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_EQ(comic_sfm(), 0);
  fs::permissions(cache, fs::perms::owner_all);
  EXPECT_EQ(ReadBytes(err_file), "");
  EXPECT_NE(ReadBytes(out_file).find("[harris] tracks read from --cache"), std::string::npos)
      << ReadBytes(out_file);
}

}  // namespace
