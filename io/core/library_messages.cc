#include "io/core/library_messages.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cctype>
#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <opencv2/core/utils/logger.hpp>

#include "io/core/printable_text.h"

namespace comic::io {
namespace {

// FFmpeg's AV_LOG_ERROR: OpenCV sets FFmpeg's level there, so these are the lines it printed.
constexpr int kFfmpegErrorLevel = 16;
// What FFmpeg may write between two captures before its lines are dropped.
constexpr size_t kMaxPendingFfmpegBytes = 65536;

using AvLogCallback = void (*)(void*, int, const char*, va_list);
using AvLogSetCallback = void (*)(AvLogCallback);
using AvLogFormatLine = void (*)(void*, int, const char*, va_list, char*, int, int*);

std::mutex& FfmpegMutex() {
  static std::mutex mutex;
  return mutex;
}

// FFmpeg's lines since the last capture took them.
std::string& PendingFfmpegLines() {
  static std::string lines;
  return lines;
}

AvLogFormatLine& FormatFfmpegLine() {
  static AvLogFormatLine format = nullptr;
  return format;
}

// FFmpeg decodes in threads of its own: a frame decoded ahead by another thread reports its
// damage after the call that started it has returned, outside any redirection of stderr. Taking
// FFmpeg's lines at their source keeps them off the terminal whenever they come; the next
// capture turns them into its message.
void KeepFfmpegLine(void* context, int level, const char* format, va_list arguments) {
  if (level > kFfmpegErrorLevel) return;
  const std::lock_guard<std::mutex> lock(FfmpegMutex());
  static int print_prefix = 1;  // FFmpeg's own state: a line continued needs no new prefix
  char line[1024];
  FormatFfmpegLine()(context, level, format, arguments, line, sizeof(line), &print_prefix);
  std::string& pending = PendingFfmpegLines();
  if (pending.size() < kMaxPendingFfmpegBytes) pending += line;
}

// FFmpeg is not a dependency of ours but of OpenCV's video module, loaded with it: its logger is
// looked up by name, and when OpenCV was built without FFmpeg there is nothing to route.
void RouteFfmpegLogging() {
  static std::once_flag once;
  std::call_once(once, [] {
    const auto set_callback =
        reinterpret_cast<AvLogSetCallback>(::dlsym(RTLD_DEFAULT, "av_log_set_callback"));
    FormatFfmpegLine() =
        reinterpret_cast<AvLogFormatLine>(::dlsym(RTLD_DEFAULT, "av_log_format_line"));
    if (set_callback != nullptr && FormatFfmpegLine() != nullptr) set_callback(&KeepFfmpegLine);
  });
}

std::string TakeFfmpegLines() {
  const std::lock_guard<std::mutex> lock(FfmpegMutex());
  std::string lines;
  lines.swap(PendingFfmpegLines());
  return lines;
}

}  // namespace

void SilenceLibraryLogging() {
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  RouteFfmpegLogging();
}

std::string CaptureLibraryMessages(const std::function<void()>& body) {
  // The process has one stderr: two overlapping redirections would restore the wrong one.
  static std::mutex redirect_mutex;
  const std::lock_guard<std::mutex> lock(redirect_mutex);
  std::FILE* sink = std::tmpfile();
  if (sink == nullptr) {  // no temp space: decode anyway, messages pass through
    body();
    return PrintableOneLine(TakeFfmpegLines(), 200);
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
  captured += TakeFfmpegLines();
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
