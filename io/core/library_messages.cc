#include "io/core/library_messages.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <mutex>
#include <opencv2/core/utils/logger.hpp>

#include "io/core/printable_text.h"

namespace comic::io {

void SilenceLibraryLogging() {
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
}

std::string CaptureLibraryMessages(const std::function<void()>& body) {
  // The process has one stderr: two overlapping redirections would restore the wrong one.
  static std::mutex redirect_mutex;
  const std::lock_guard<std::mutex> lock(redirect_mutex);
  std::FILE* sink = std::tmpfile();
  if (sink == nullptr) {  // no temp space: decode anyway, messages pass through
    body();
    return "";
  }
  std::fflush(stderr);
  const int saved = ::dup(2);
  const bool redirected = saved >= 0 && ::dup2(::fileno(sink), 2) >= 0;
  auto restore = [&] {
    std::fflush(stderr);
    if (redirected) ::dup2(saved, 2);
    if (saved >= 0) ::close(saved);
  };
  try {
    body();
  } catch (...) {
    restore();
    std::fclose(sink);
    throw;
  }
  restore();
  std::string captured;
  std::rewind(sink);
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof(buffer), sink)) > 0 && captured.size() < 65536) {
    captured.append(buffer, n);
  }
  std::fclose(sink);
  // FFmpeg names its context by address ("[mjpeg @ 0x55eafc5bb040] overread 8"): meaningless to
  // a user and different on every run, so the address goes.
  for (size_t at = captured.find(" @ 0x"); at != std::string::npos; at = captured.find(" @ 0x")) {
    size_t end = at + 5;
    while (end < captured.size() && std::isxdigit(static_cast<unsigned char>(captured[end]))) ++end;
    captured.erase(at, end - at);
  }
  return PrintableOneLine(captured, 200);
}

bool MessageReportsCorruptData(const std::string& message) {
  for (const char* word : {"Premature end", "Corrupt", "corrupt", "error", "Error", "overread",
                           "invalid", "Invalid", "truncated"}) {
    if (message.find(word) != std::string::npos) return true;
  }
  return false;
}

}  // namespace comic::io
