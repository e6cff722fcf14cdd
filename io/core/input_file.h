// Inputs that never hang: what a run reads is looked at (stat, which never blocks) before it is
// opened. A named FIFO blocks open() until a writer comes, a socket or a device never ends, so
// they are refused at once; a pipe the shell hands over as /dev/fd/N (`--intrinsics <(cat
// calib.txt)`), /proc/self/fd/N or /dev/stdin is a stream: it is read once, as it comes.
//
//   io::CheckInputFile(path, "--intrinsics");  // then open and read it once
#pragma once

#include <string>

namespace comic::io {

// True for /dev/stdin, /dev/fd/N and /proc/self/fd/N: a stream handed over by the shell.
bool IsStreamPath(const std::string& path);

// Throws comic::Error naming `path` if it cannot be read as a file without blocking: missing
// (kNotFound), a folder (kInvalidArgument), or a FIFO, socket or device that is not a stream
// path (kInvalidData, "not a regular file (a FIFO)"). A regular file and a stream pass.
void CheckInputFile(const std::string& path);

}  // namespace comic::io
