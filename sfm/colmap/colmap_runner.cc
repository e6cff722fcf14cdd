#include "sfm/colmap/colmap_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/colmap/colmap_text_model.h"
#include "io/core/error.h"
#include "io/core/file_utils.h"

extern char** environ;

namespace comic::sfm {
namespace {

namespace fs = std::filesystem;

bool IsExecutableFile(const std::string& path) {
  return io::IsRegularFile(path) && ::access(path.c_str(), X_OK) == 0;
}

std::string FormatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// The last non-empty line of a file (reading at most its last 8 KiB), for error messages.
std::string LastLineOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff start = std::max<std::streamoff>(0, size - 8192);
  in.seekg(start);
  std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r' || tail.back() == ' ')) {
    tail.pop_back();
  }
  const size_t newline = tail.find_last_of('\n');
  return newline == std::string::npos ? tail : tail.substr(newline + 1);
}

size_t FileSize(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? 0 : static_cast<size_t>(size);
}

bool IsAllDigits(const std::string& text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

double ChildrenCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

bool IsColmapAvailable(const std::string& executable) {
  if (executable.empty()) return false;
  if (executable.find('/') != std::string::npos) return IsExecutableFile(executable);
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (IsExecutableFile(io::JoinPaths(dir.empty() ? "." : dir, executable))) return true;
  }
  return false;
}

std::string ShellCommandLine(const std::vector<std::string>& args) {
  std::string line;
  for (const std::string& arg : args) {
    if (!line.empty()) line += ' ';
    const bool plain = !arg.empty() && std::all_of(arg.begin(), arg.end(), [](unsigned char c) {
      return std::isalnum(c) || std::strchr("_-./:=+,@%", c) != nullptr;
    });
    if (plain) {
      line += arg;
      continue;
    }
    line += '\'';
    for (char c : arg) {
      if (c == '\'') {
        line += "'\\''";
      } else {
        line += c;
      }
    }
    line += '\'';
  }
  return line;
}

void RunColmap(const std::vector<std::string>& args, const std::string& log_path,
               const std::string& executable) {
  COMIC_CHECK(!executable.empty(), kInvalidArgument, "COLMAP executable name is empty");
  COMIC_CHECK(!log_path.empty(), kInvalidArgument, "COLMAP log path is empty");
  std::vector<std::string> command_args = {executable};
  command_args.insert(command_args.end(), args.begin(), args.end());
  const std::string command = ShellCommandLine(command_args);
  {
    std::ofstream log(log_path, std::ios::app);
    COMIC_CHECK(log.good(), kIo, log_path << ": cannot open the COLMAP log for writing");
    log << "$ " << command << "\n";
    COMIC_CHECK(log.good(), kIo, log_path << ": cannot write the COLMAP log");
  }

  // The child's environment: ours, with Qt told not to look for a display.
  std::vector<std::string> env_strings;
  for (char** entry = environ; entry != nullptr && *entry != nullptr; ++entry) {
    if (std::strncmp(*entry, "QT_QPA_PLATFORM=", 16) != 0) env_strings.emplace_back(*entry);
  }
  env_strings.emplace_back("QT_QPA_PLATFORM=offscreen");
  std::vector<char*> envp;
  for (std::string& entry : env_strings) envp.push_back(entry.data());
  envp.push_back(nullptr);
  std::vector<char*> argv;
  for (std::string& arg : command_args) argv.push_back(arg.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                   O_WRONLY | O_APPEND | O_CREAT, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  // The apps block SIGINT/SIGTERM in every thread (io/core/interrupt_cleanup.h); COLMAP must not
  // inherit that mask, or Ctrl-C would leave it running.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t no_signals;
  sigemptyset(&no_signals);
  posix_spawnattr_setsigmask(&attributes, &no_signals);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = -1;
  const int spawn_error =
      posix_spawnp(&pid, executable.c_str(), &actions, &attributes, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  COMIC_CHECK(
      spawn_error == 0, kExternal,
      command << ": cannot start " << executable << ": " << std::strerror(spawn_error)
              << (spawn_error == ENOENT ? " (is COLMAP installed? apt-get install colmap)" : ""));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    COMIC_CHECK(errno == EINTR, kExternal,
                command << ": waiting for COLMAP failed: " << std::strerror(errno));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  std::ostringstream what;
  if (WIFEXITED(status)) {
    what << "exit status " << WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    what << "killed by signal " << WTERMSIG(status);
  } else {
    what << "status " << status;
  }
  throw Error(ErrorKind::kExternal, command + " failed (" + what.str() +
                                        "): " + LastLineOf(log_path) + " (log: " + log_path + ")");
}

void ColmapMapperOptions::Check() const {
  COMIC_CHECK(num_threads == -1 || num_threads >= 1, kInvalidArgument,
              "COLMAP mapper num_threads must be -1 or >= 1, got " << num_threads);
  COMIC_CHECK(
      init_max_forward_motion > 0 && init_max_forward_motion <= 1, kInvalidArgument,
      "COLMAP mapper init_max_forward_motion must be in (0, 1], got " << init_max_forward_motion);
  COMIC_CHECK(
      init_min_tri_angle > 0 && init_min_tri_angle < 90, kInvalidArgument,
      "COLMAP mapper init_min_tri_angle must be in (0, 90) degrees, got " << init_min_tri_angle);
  COMIC_CHECK(min_model_size >= 2, kInvalidArgument,
              "COLMAP mapper min_model_size must be >= 2, got " << min_model_size);
}

ColmapMapperOptions RecommendedColmapMapperOptions(const ColmapExportSummary& summary) {
  ColmapMapperOptions options;
  if (summary.num_pairs_allowing_default_init == 0) options.init_max_forward_motion = 1.0;
  const double angle = summary.max_init_triangulation_angle_deg;
  if (angle > 0 && angle < options.init_min_tri_angle) {
    options.init_min_tri_angle = std::max(0.1, std::floor(angle / 2.0 * 10.0) / 10.0);
  }
  if (summary.known_intrinsics) {
    options.ba_refine_focal_length = false;
    options.ba_refine_principal_point = false;
    options.ba_refine_extra_params = false;
  }
  options.min_model_size =
      std::min(options.min_model_size, std::max(3, (summary.num_images + 3) / 4));
  return options;
}

std::vector<std::string> ColmapMapperArguments(const std::string& database_path,
                                               const std::string& image_path,
                                               const std::string& output_path,
                                               const ColmapMapperOptions& options) {
  options.Check();
  std::vector<std::string> args = {"mapper",   "--database_path", database_path, "--image_path",
                                   image_path, "--output_path",   output_path};
  if (options.num_threads != -1) {
    args.insert(args.end(), {"--Mapper.num_threads", std::to_string(options.num_threads)});
  }
  args.insert(args.end(),
              {"--Mapper.init_max_forward_motion", FormatNumber(options.init_max_forward_motion),
               "--Mapper.init_min_tri_angle", FormatNumber(options.init_min_tri_angle),
               "--Mapper.ba_refine_focal_length", options.ba_refine_focal_length ? "1" : "0",
               "--Mapper.ba_refine_principal_point", options.ba_refine_principal_point ? "1" : "0",
               "--Mapper.ba_refine_extra_params", options.ba_refine_extra_params ? "1" : "0",
               "--Mapper.min_model_size", std::to_string(options.min_model_size)});
  return args;
}

std::string ColmapMapperOutputBeside(const std::string& database_path) {
  return io::JoinPaths(io::JoinPaths(io::ParentPath(database_path), "colmap"), "sparse");
}

std::string ColmapMapperCommandLine(const std::string& database_path, const std::string& image_path,
                                    const std::string& output_path,
                                    const ColmapMapperOptions& options) {
  std::vector<std::string> args = {"colmap"};
  const auto mapper = ColmapMapperArguments(database_path, image_path, output_path, options);
  args.insert(args.end(), mapper.begin(), mapper.end());
  return ShellCommandLine({"mkdir", "-p", output_path}) + " && " + ShellCommandLine(args);
}

std::optional<std::string> RunColmapMapper(const std::string& database_path,
                                           const std::string& image_path,
                                           const std::string& output_path,
                                           const ColmapMapperOptions& options,
                                           const std::string& log_path,
                                           const std::string& executable) {
  options.Check();
  COMIC_CHECK(io::IsRegularFile(database_path), kNotFound,
              database_path << ": no such COLMAP database");
  COMIC_CHECK(io::IsDirectory(image_path), kNotFound, image_path << ": no such image folder");
  io::EnsureWritableDirectory(output_path);
  COMIC_CHECK(!FindLargestColmapModel(output_path), kIo,
              output_path << ": holds COLMAP models already (use an empty folder)");
  const size_t log_offset = FileSize(log_path);
  try {
    RunColmap(ColmapMapperArguments(database_path, image_path, output_path, options), log_path,
              executable);
  } catch (const Error& e) {
    // COLMAP 3.8 exits with status 1 when it finds no initial pair: an expected outcome, not an
    // error of the program.
    const std::string log = io::ReadFileToString(log_path);
    const bool no_initial_pair = e.kind() == ErrorKind::kExternal &&
                                 log.find("No good initial image pair found",
                                          std::min(log_offset, log.size())) != std::string::npos;
    if (!no_initial_pair || FindLargestColmapModel(output_path)) throw;
  }
  return FindLargestColmapModel(output_path);
}

int64_t NumRegisteredImagesOfColmapModel(const std::string& model_path) {
  const std::string bin = io::JoinPaths(model_path, "images.bin");
  if (io::IsRegularFile(bin)) {
    std::ifstream in(bin, std::ios::binary);
    uint64_t num_images = 0;
    in.read(reinterpret_cast<char*>(&num_images), sizeof(num_images));
    COMIC_CHECK(in.gcount() == sizeof(num_images), kInvalidData,
                bin << ": too short for a COLMAP images file");
    return static_cast<int64_t>(num_images);
  }
  COMIC_CHECK(io::IsRegularFile(io::JoinPaths(model_path, "images.txt")), kNotFound,
              model_path << ": no images.bin or images.txt (not a COLMAP model)");
  return static_cast<int64_t>(io::ReadColmapTextModel(model_path).images.size());
}

std::optional<std::string> FindLargestColmapModel(const std::string& output_path) {
  if (!io::IsDirectory(output_path)) return std::nullopt;
  std::vector<std::pair<long long, std::string>> models;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(output_path, ec)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || !IsAllDigits(name) || name.size() > 9) continue;
    const std::string path = entry.path().string();
    if (io::IsRegularFile(io::JoinPaths(path, "images.bin")) ||
        io::IsRegularFile(io::JoinPaths(path, "images.txt"))) {
      models.emplace_back(std::stoll(name), path);
    }
  }
  std::sort(models.begin(), models.end());
  std::optional<std::string> largest;
  int64_t largest_size = -1;
  for (const auto& model : models) {
    const int64_t size = NumRegisteredImagesOfColmapModel(model.second);
    if (size > largest_size) {
      largest_size = size;
      largest = model.second;
    }
  }
  return largest;
}

ColmapModelStats ParseColmapModelAnalyzerOutput(const std::string& text) {
  // The value after "<key>:" on the last line that starts with the key, once a glog prefix
  // ("I1126 11:30:04.123 4242 model.cc:12] ") is removed.
  const auto find = [&](const std::string& key) -> double {
    std::istringstream lines(text);
    std::string line;
    std::optional<double> value;
    while (std::getline(lines, line)) {
      const size_t bracket = line.find("] ");
      if (bracket != std::string::npos && !line.empty() && std::strchr("IWEF", line[0])) {
        line = line.substr(bracket + 2);
      }
      if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
      const char* begin = line.c_str() + key.size() + 1;
      char* end = nullptr;
      const double parsed = std::strtod(begin, &end);
      if (end != begin) value = parsed;
    }
    COMIC_CHECK(value.has_value(), kInvalidData,
                "COLMAP model_analyzer output has no '" << key << "' line");
    return *value;
  };
  ColmapModelStats stats;
  stats.num_cameras = static_cast<int64_t>(find("Cameras"));
  stats.num_images = static_cast<int64_t>(find("Images"));
  stats.num_registered_images = static_cast<int64_t>(find("Registered images"));
  stats.num_points3D = static_cast<int64_t>(find("Points"));
  stats.num_observations = static_cast<int64_t>(find("Observations"));
  stats.mean_track_length = find("Mean track length");
  stats.mean_observations_per_image = find("Mean observations per image");
  stats.mean_reprojection_error = find("Mean reprojection error");
  return stats;
}

ColmapModelStats AnalyzeColmapModel(const std::string& model_path, const std::string& log_path,
                                    const std::string& executable) {
  COMIC_CHECK(io::IsDirectory(model_path), kNotFound, model_path << ": no such COLMAP model");
  const size_t offset = FileSize(log_path);
  RunColmap({"model_analyzer", "--path", model_path}, log_path, executable);
  const std::string log = io::ReadFileToString(log_path);
  try {
    return ParseColmapModelAnalyzerOutput(log.substr(std::min(offset, log.size())));
  } catch (const Error& e) {
    throw Error(ErrorKind::kExternal, std::string(e.what()) + " (log: " + log_path + ")");
  }
}

void ConvertColmapModel(const std::string& input_path, const std::string& output_path,
                        const std::string& output_type, const std::string& log_path,
                        const std::string& executable) {
  COMIC_CHECK(output_type == "TXT" || output_type == "BIN", kInvalidArgument,
              "COLMAP model output type must be TXT or BIN, got '" << output_type << "'");
  COMIC_CHECK(io::IsDirectory(input_path), kNotFound, input_path << ": no such COLMAP model");
  io::EnsureWritableDirectory(output_path);
  RunColmap({"model_converter", "--input_path", input_path, "--output_path", output_path,
             "--output_type", output_type},
            log_path, executable);
}

ColmapBundleAdjustmentTimes ParseColmapBundleAdjustmentTimes(const std::string& log_text) {
  ColmapBundleAdjustmentTimes times;
  // The last mapper run of the log.
  size_t begin = 0;
  for (size_t pos = 0; (pos = log_text.find("$ ", pos)) != std::string::npos; ++pos) {
    const size_t end_of_line = log_text.find('\n', pos);
    const std::string command = log_text.substr(pos, end_of_line - pos);
    if ((pos == 0 || log_text[pos - 1] == '\n') && command.find(" mapper ") != std::string::npos) {
      begin = pos;
    }
  }
  // ... up to the next command of the log.
  const size_t end = log_text.find("\n$ ", begin);
  std::istringstream lines(
      log_text.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
  std::string line, previous, heading;
  while (std::getline(lines, line)) {
    // PrintHeading1: the title between two lines of '='.
    if (!line.empty() && line.find_first_not_of('=') == std::string::npos && !previous.empty() &&
        previous.find_first_not_of('=') != std::string::npos &&
        previous.find_first_not_of(' ') != std::string::npos) {
      heading = previous;
    }
    const size_t time = line.find("Time : ");
    if (time != std::string::npos && line.find("[s]") != std::string::npos) {
      const double seconds = std::strtod(line.c_str() + time + 7, nullptr);
      if (heading.find("Global bundle adjustment") != std::string::npos) {
        times.global_s += seconds;
        ++times.num_global;
      } else {
        times.local_s += seconds;
        ++times.num_local;
      }
    }
    previous = line;
  }
  return times;
}

}  // namespace comic::sfm
