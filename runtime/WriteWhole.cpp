#include "WriteWhole.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <fstream>

#include <fmt/format.h>

namespace gbx::rt {

namespace {

// The temporary file being written, for the signal handler: Ctrl-C (or a kill) while a
// report is written removes it, and the old file stays as it was.
char gPending[4096];
volatile std::sig_atomic_t gHasPending = 0;

void removePendingAndStop(int sig) {
  if (gHasPending) ::unlink(gPending); // async-signal-safe
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// Installed once, and only over the default action (a host's own handler is kept).
void installSignalCleanup() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_DFL) std::signal(sig, removePendingAndStop);
    }
    return true;
  }();
  (void)installed;
}

} // namespace

std::string writeWhole(const std::filesystem::path& written, const std::string& text) {
  static std::atomic<unsigned> serial{0};
  installSignalCleanup();
  // Through a symbolic link to the file it names: renaming over the link would replace the
  // link, and leave the file as it was.
  std::filesystem::path path = written;
  {
    std::error_code ec;
    if (std::filesystem::is_symlink(written, ec))
      if (auto real = std::filesystem::canonical(written, ec); !ec) path = real;
  }
  std::filesystem::path tmp = path;
  tmp += fmt::format(".tmp-{}-{}", static_cast<long>(getpid()), serial++);
  std::error_code ec;
  const std::string& t = tmp.string();
  if (t.size() < sizeof gPending) {
    std::copy(t.begin(), t.end(), gPending);
    gPending[t.size()] = '\0';
    std::atomic_signal_fence(std::memory_order_seq_cst); // the path is whole before the flag says so
    gHasPending = 1;
  }
  struct Done {
    ~Done() { gHasPending = 0; }
  } done;
  {
    std::ofstream f(tmp, std::ios::binary);
    if (f) {
      f << text;
      f.close();
    }
    if (!f) {
      std::filesystem::remove(tmp, ec);
      return fmt::format("cannot write `{}` (an unwritable folder, or a full disk)", path.string());
    }
  }
  // A file rewritten in place (`gbxc fmt`) keeps its permissions, and its owner where the
  // writer may give it (as root).
  if (auto st = std::filesystem::status(path, ec); !ec && std::filesystem::is_regular_file(st)) {
    std::filesystem::permissions(tmp, st.permissions(), ec);
    struct stat old {};
    if (::stat(path.c_str(), &old) == 0 && ::chown(tmp.c_str(), old.st_uid, old.st_gid) != 0) {
      // Another owner is not ours to give: the file becomes the writer's, as any editor's would.
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    return fmt::format("cannot write `{}`: {}", path.string(), ec.message());
  }
  return {};
}

} // namespace gbx::rt
