#include "apps/common/progress_line.h"

#include <unistd.h>

#include <cstdio>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace comic::apps {

ProgressLine::ProgressLine(std::string label, bool quiet, std::ostream* out, int terminal,
                           std::function<double()> seconds_since_start)
    : label_(std::move(label)),
      quiet_(quiet),
      out_(out != nullptr ? out : &std::cout),
      terminal_(terminal < 0 ? ::isatty(::fileno(stdout)) == 1 : terminal != 0),
      seconds_since_start_(std::move(seconds_since_start)) {
  if (!seconds_since_start_) {
    const auto start = std::chrono::steady_clock::now();
    seconds_since_start_ = [start] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
  }
}

std::string ProgressLine::Format(const std::string& label, size_t done, size_t total,
                                 double elapsed_s) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << label << ": frame " << done;
  if (total > 0) text << "/" << total;
  text << ", " << elapsed_s << " s elapsed";
  if (total > 0 && done > 0 && done < total) {
    text << ", about " << elapsed_s / static_cast<double>(done) * static_cast<double>(total - done)
         << " s left";
  }
  return text.str();
}

void ProgressLine::Update(size_t done, size_t total) {
  if (quiet_) return;
  const std::string text = Format(label_, done, total, seconds_since_start_());
  if (terminal_) {
    // "\33[K" clears what a longer previous text left on the line.
    *out_ << "\r" << text << "\33[K";
    if (done >= total) *out_ << "\n";
    out_->flush();
  } else {
    *out_ << text << std::endl;
  }
}

std::function<void(size_t, size_t)> ProgressLine::Callback() {
  return [this](size_t done, size_t total) { Update(done, total); };
}

}  // namespace comic::apps
