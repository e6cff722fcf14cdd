// What the libFuzzer targets share: the fuzzer's bytes as a file (the readers under test take
// paths), in a private folder under /dev/shm (or the temp folder) removed at exit, and the rule
// that comic::Error is the expected answer to bad input while anything else (a crash, a sanitizer
// report, another exception escaping) is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace comic::fuzz {

// A folder for this fuzzing process, created once and removed when the process ends.
inline const std::string& ScratchDir() {
  struct Scratch {
    std::string path;
    Scratch() {
      std::error_code ec;
      const std::filesystem::path base = std::filesystem::is_directory("/dev/shm", ec)
                                             ? std::filesystem::path("/dev/shm")
                                             : std::filesystem::temp_directory_path();
      path = (base / ("comic_fuzz_" + std::to_string(::getpid()))).string();
      std::filesystem::create_directories(path, ec);
    }
    ~Scratch() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static Scratch scratch;
  return scratch.path;
}

// Writes the bytes to ScratchDir()/name and returns the path.
inline std::string WriteInput(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = ScratchDir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace comic::fuzz
