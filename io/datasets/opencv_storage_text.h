// The part of OpenCV's FileStorage text formats a camera calibration is written in, checked before
// any byte reaches cv::FileStorage. OpenCV 4.6's YAML and XML parsers loop forever, read out of
// bounds or dereference null on some malformed files (fuzz_calibration_values found three), and
// an allow-list is the only defence that does not wait for the next one: what calibrateCamera's
// users save (cv::FileStorage's own YAML and XML output, ROS camera_info YAML) passes, everything
// else is refused with one line naming the file and line.
//
// YAML: an optional "%YAML" directive, "---" and "..." markers, whole-line '#' comments, and
// "key: value" lines two levels deep (a key with no value or "!!opencv-matrix" opens the second
// level); a value is a number, a plain word or words, a double-quoted string without escapes, or
// a '[' sequence of numbers that may continue over lines up to its ']'.
// XML: an "<?xml ...?>" declaration, <!-- comments -->, and elements nested at most three deep
// under one root (each with optional name="value" attributes), whose text is printable ASCII.
#pragma once

#include <string>

namespace comic::io {

// The format is the one cv::FileStorage picks when it reads: the text (after a UTF-8 byte-order
// mark) starts with "%YAML" or "<?xml"; any other start is refused too. Throws comic::Error
// (kInvalidData) naming `path` and the first line outside the subset.
void CheckOpenCvStorageText(const std::string& text, const std::string& path);

}  // namespace comic::io
