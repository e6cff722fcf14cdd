// Third-party libraries print their own lines on stderr (OpenCV's log, libpng's "libpng error:
// Read Error", libjpeg's "Premature end of JPEG file", FFmpeg's "moov atom not found"), which
// breaks the apps' promise of one line, ours, naming the file. These helpers silence the loggers
// that can be silenced and capture what the others write, so that the caller turns it into its
// own message (issue 19).
#pragma once

#include <functional>
#include <string>

namespace comic::io {

// Sets OpenCV's own log level to silent ("[ WARN:0@0.1] global cap_gstreamer.cpp ..."). FFmpeg's
// lines (OpenCV leaves them at AV_LOG_ERROR) say where a stream breaks, so they are not dropped
// but kept from stderr at their source (FFmpeg's log callback), whichever decoding thread writes
// them and whenever, and handed to the next CaptureLibraryMessages. Idempotent; called by the
// apps' main and before this library opens a video.
void SilenceLibraryLogging();

// Runs `body` with the process's stderr (file descriptor 2) redirected to an anonymous temporary
// file and returns what was written there meanwhile, with FFmpeg's lines kept since the last
// call, as one printable line (empty if nothing).
// Calls are serialised (fd 2 is one per process); exceptions from `body` propagate after stderr
// is restored. Used around decoders whose libraries print instead of reporting.
std::string CaptureLibraryMessages(const std::function<void()>& body);

// True if a captured library message says that the data was corrupt or ended early (libjpeg's
// "Premature end" / "Corrupt JPEG data", libpng's "error", FFmpeg's "overread"/"invalid"), as
// opposed to a harmless warning such as libpng's "iCCP: known incorrect sRGB profile".
bool MessageReportsCorruptData(const std::string& message);

}  // namespace comic::io
