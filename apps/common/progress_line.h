// Progress of an app's long per-frame work (detection and tracking, writing video frames;
// issue 17): "[harris] tracking: frame 5/51, 4.1 s elapsed, about 37.8 s left". The libraries
// only call back (frontend::TrackingProgress, io::FrameExportProgress); this prints. It goes to
// stdout, one line per frame, or one line rewritten with '\r' when stdout is a terminal, so that
// stderr keeps its promise of one line for an error (issue 19) and progress appears only once
// the work has started. --quiet makes it silent.
//
//   ProgressLine progress("[harris] tracking", flags.quiet);
//   TrackSequence(sequence, *detector, options, progress.Callback());
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>

namespace comic::apps {

class ProgressLine {
 public:
  // `label` starts every line. `out` defaults to std::cout, `terminal` to whether stdout is one;
  // `seconds_since_start` (tests) replaces the steady clock started at construction.
  ProgressLine(std::string label, bool quiet, std::ostream* out = nullptr, int terminal = -1,
               std::function<double()> seconds_since_start = {});

  // Reports `done` of `total` frames (total 0: unknown, no estimate). The estimate of what
  // remains assumes the remaining frames cost what the done ones cost on average.
  void Update(size_t done, size_t total);
  // Update as a callback for the libraries; valid while this object lives.
  std::function<void(size_t, size_t)> Callback();

  // The text of one update, without line ending ("label: frame 5/51, 4.1 s elapsed, about 37.8 s
  // left").
  static std::string Format(const std::string& label, size_t done, size_t total, double elapsed_s);

 private:
  std::string label_;
  bool quiet_;
  std::ostream* out_;
  bool terminal_;
  std::function<double()> seconds_since_start_;
};

}  // namespace comic::apps
