#include "io/module/module_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <pthread.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <condition_variable>
#include <csignal>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "io/io_error.h"
#include "io/files/signals.h"

namespace raycast::io {
namespace {

std::string executable_dir() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string path(buf, size_t(n));
  return path.substr(0, path.find_last_of('/'));
}

// While the image module loads: a thread that takes the signals (a library may deadlock in
// static constructors, in threads that block every signal) and fails the load after load_timeout.
class load_watchdog {
 public:
  static constexpr auto load_timeout = std::chrono::seconds(30);

  load_watchdog() {
    try {
      thread_ = std::thread([this] {
        sigset_t all;
        sigfillset(&all);
        pthread_sigmask(SIG_UNBLOCK, &all, nullptr);
        std::unique_lock<std::mutex> lock(m_);
        if (!done_cv_.wait_for(lock, load_timeout, [this] { return done_; }))
          crash_means_failure::fail("its libraries did not finish starting in 30 s");
      });
    } catch (const std::system_error&) {  // no thread to spare: no watchdog
    }
  }
  ~load_watchdog() {
    if (!thread_.joinable()) return;
    {
      const std::lock_guard<std::mutex> lock(m_);
      done_ = true;
    }
    done_cv_.notify_one();
    thread_.join();
  }
  load_watchdog(const load_watchdog&) = delete;
  load_watchdog& operator=(const load_watchdog&) = delete;

 private:
  std::mutex m_;
  std::condition_variable done_cv_;
  bool done_ = false;
  std::thread thread_;
};

std::vector<std::string>& extra_dirs() {
  static std::vector<std::string> dirs;
  return dirs;
}

}  // namespace

void add_image_module_dir(const std::string& dir) {
  auto& dirs = extra_dirs();
  if (std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) dirs.push_back(dir);
}

const raycast_image_module* load_image_module(const std::string& for_file) {
  static const raycast_image_module* cached = nullptr;
  if (cached) return cached;
  const std::string dir = executable_dir();
  // The error to report: the first present candidate's, else the first's.
  std::string first_error, first_present_error;
  const std::string what = for_file + ": cannot load the image module";
  std::vector<std::string> candidates;
  for (const std::string& d : extra_dirs()) candidates.push_back(d + "/raycast_oiio.so");
  candidates.push_back(dir + "/raycast_oiio.so");
  candidates.push_back(dir + "/" RAYCAST_MODULE_RELDIR "/raycast_oiio.so");
  // OpenBLAS (a dependency) starts a thread pool as it loads; raycast never calls BLAS.
  ::setenv("OPENBLAS_NUM_THREADS", "1", 0);
  for (const std::string& candidate : candidates) {
    std::string error;
    {
      // dlopen runs static constructors that crash when memory or threads run short.
      const crash_means_failure crash(what);
      const load_watchdog watchdog;
      if (void* h = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL)) {
        using get_fn = const raycast_image_module* (*)();
        auto get = reinterpret_cast<get_fn>(dlsym(h, "raycast_image_module_get"));
        const raycast_image_module* m = get ? get() : nullptr;
        if (m && m->abi_version == RAYCAST_IMAGE_MODULE_ABI) return cached = m;
        error = candidate + ": not a raycast image module of this version";
      } else {
        const char* e = dlerror();
        error = e ? e : candidate;
      }
    }
    if (first_error.empty()) first_error = error;
    if (first_present_error.empty() && access(candidate.c_str(), F_OK) == 0) first_present_error = error;
  }
  throw io_error(what + " (" + (first_present_error.empty() ? first_error : first_present_error) + ")");
}

}  // namespace raycast::io
