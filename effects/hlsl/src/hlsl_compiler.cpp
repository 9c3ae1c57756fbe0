// Public entry points, and crash isolation: glslang 12's HLSL front end and the
// SPIRV-Tools legalization passes segfault on some malformed sources (found by
// fuzzing), so by default compiles run in a forked worker process that sends
// the CompileResult back through a socket. A crash or hang there becomes an
// error and the worker is replaced.
#include "hlsl/hlsl_compiler.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <sstream>
#include <type_traits>

#include "internal.h"

namespace hlsl {
namespace {

constexpr int kWorkerTimeoutMs = 60'000;

// The sanitizers' allocators (GCC 12's libasan at least) are not fork-safe: a
// child forked while another thread allocates deadlocks. Those builds compile
// in-process, and the sanitizer reports any crash inside glslang.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kCanFork = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kCanFork = false;
#else
constexpr bool kCanFork = true;
#endif
#else
constexpr bool kCanFork = true;
#endif

CompileResult ErrorResult(const CompileRequest& request, std::string message) {
  CompileResult result;
  result.errors.push_back({detail::SourceName(request), 0, 0, std::move(message)});
  return result;
}

CompileResult CompileGuarded(const CompileRequest& request) {
  try {
    return detail::CompileInProcess(request);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc; the API promises not to throw
    return ErrorResult(request, std::string("internal compiler error: ") + e.what());
  }
}

// --- Requests and results <-> bytes. Each struct lists its fields once, in Fields().

// What the worker needs besides the request: relative paths resolve against
// the caller's current directory, which may have changed since the fork.
struct Job {
  std::string cwd;
  CompileRequest request;
};

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};

template <class A>
void Fields(A& a, Diagnostic& d) {
  a(d.file, d.line, d.column, d.message);
}
template <class A>
void Fields(A& a, ConstantBufferMember& m) {
  a(m.name, m.offset, m.size, m.baseType, m.rows, m.columns, m.arrayElements);
}
template <class A>
void Fields(A& a, ConstantBufferInfo& c) {
  a(c.name, c.binding, c.registerSlot, c.size, c.members);
}
template <class A>
void Fields(A& a, ResourceInfo& r) {
  a(r.name, r.binding, r.registerSlot, r.kind, r.dimension, r.bindCount, r.comparisonSampler, r.isCounter);
}
template <class A>
void Fields(A& a, CompileResult& r) {
  a(r.ok, r.spirv, r.stage, r.errors, r.warnings, r.constantBuffers, r.resources);
}
template <class A>
void Fields(A& a, Define& d) {
  a(d.name, d.value);
}
template <class A>
void Fields(A& a, CompileRequest& r) {
  a(r.source, r.fileName, r.entryPoint, r.profile, r.defines, r.includeDirs, r.isolate);
}
template <class A>
void Fields(A& a, Job& j) {
  a(j.cwd, j.request);
}

struct Writer {
  std::string bytes;
  template <class... T>
  void operator()(T&... values) {
    (Put(values), ...);
  }
  template <class T>
  void Put(T& v) {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    } else if constexpr (std::is_same_v<T, std::string> || IsVector<T>::value) {
      uint64_t n = v.size();
      Put(n);
      for (auto& e : v) Put(e);
    } else {
      Fields(*this, v);
    }
  }
};

struct Reader {
  std::string_view bytes;
  bool ok = true;
  template <class... T>
  void operator()(T&... values) {
    (Get(values), ...);
  }
  template <class T>
  void Get(T& v) {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      if (bytes.size() < sizeof v) return void(ok = false);
      std::memcpy(&v, bytes.data(), sizeof v);
      bytes.remove_prefix(sizeof v);
    } else if constexpr (std::is_same_v<T, std::string> || IsVector<T>::value) {
      uint64_t n = 0;
      Get(n);
      if (!ok || n > bytes.size()) return void(ok = false);  // every element takes at least a byte
      v.resize(n);
      for (auto& e : v) Get(e);
    } else {
      Fields(*this, v);
    }
  }
};

template <class T>
std::string Encode(T value) {
  Writer writer;
  writer(value);
  return std::move(writer.bytes);
}

template <class T>
bool Decode(std::string_view bytes, T& value) {
  Reader reader{bytes};
  reader(value);
  return reader.ok && reader.bytes.empty();
}

// --- The worker process

// fork() copies only the calling thread; a lock another thread holds at that
// moment stays locked in the child forever. In-process compiles (which take
// glslang's global lock) hold this shared; fork() holds it exclusively.
std::shared_mutex& ForkGate() {
  static std::shared_mutex gate;
  return gate;
}

// Builds glslang's built-in symbol tables (~40 ms, almost all shared by the
// stages) in the parent once, so workers inherit them instead of rebuilding.
void WarmUp() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::shared_lock lock(ForkGate());
    CompileGuarded({"float4 main() : SV_Position { return 0; }", "warm-up", "main", "vs_5_0", {}, {}});
  });
}

// Frames are a uint64 length and that many bytes. MSG_NOSIGNAL: a dead peer
// must give an error, not SIGPIPE.
bool SendFrame(int fd, const std::string& payload) {
  const uint64_t size = payload.size();
  std::string frame(reinterpret_cast<const char*>(&size), sizeof size);
  frame += payload;
  for (size_t done = 0; done < frame.size();) {
    const ssize_t n = send(fd, frame.data() + done, frame.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

enum class Receive { Ok, Closed, TimedOut };

Receive ReceiveBytes(int fd, char* data, size_t size, std::chrono::steady_clock::time_point deadline) {
  for (size_t done = 0; done < size;) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(std::clamp<int64_t>(left.count(), 0, INT32_MAX)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) return Receive::TimedOut;
    const ssize_t n = ready < 0 ? -1 : read(fd, data + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return Receive::Closed;
    done += static_cast<size_t>(n);
  }
  return Receive::Ok;
}

Receive ReceiveFrame(int fd, std::string& payload, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  uint64_t size = 0;
  if (Receive r = ReceiveBytes(fd, reinterpret_cast<char*>(&size), sizeof size, deadline); r != Receive::Ok) return r;
  if (size > (uint64_t{1} << 32)) return Receive::Closed;
  payload.resize(size);
  return ReceiveBytes(fd, payload.data(), size, deadline);
}

[[noreturn]] void WorkerMain(int fd) {
  // A crash must end only this process: undo any crash handler the host
  // installed. Ctrl+C is for the host; the worker ends when its socket closes.
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
  std::signal(SIGINT, SIG_IGN);
  // Nothing may print, and no other descriptor of the host stays open here:
  // the socket moves to fd 3 (via a high number, in case it was 1 or 2).
  const int channel = fcntl(fd, F_DUPFD, 10);
  if (int null = open("/dev/null", O_WRONLY); null >= 0) {
    dup2(null, 1);
    dup2(null, 2);
  }
  if (channel < 0 || dup2(channel, 3) < 0) _exit(1);
  close_range(4, ~0u, 0);
  for (std::string frame;;) {
    Job job;
    if (ReceiveFrame(3, frame, std::chrono::hours(24 * 365)) != Receive::Ok || !Decode(frame, job)) _exit(0);
    // On failure relative paths simply do not open (a missing include error).
    [[maybe_unused]] const int changed = chdir(job.cwd.c_str());
    if (!SendFrame(3, Encode(CompileGuarded(job.request)))) _exit(0);
  }
}

std::string DescribeFailure(int status, Receive how) {
  if (how == Receive::TimedOut) return "internal compiler error: the compiler did not finish within 60 s";
  if (WIFSIGNALED(status)) {
    const char* name = sigdescr_np(WTERMSIG(status));
    return std::string("internal compiler error: glslang/SPIRV-Tools crashed on this source (") +
           (name ? name : "signal " + std::to_string(WTERMSIG(status))) + ")";
  }
  return "internal compiler error: the compiler process failed";
}

// One forked compiler process per calling thread, started on first use and
// restarted after a crash. It stays warm, so a compile costs about as much as
// in-process plus copying the request and result through a socket.
class Worker {
 public:
  ~Worker() { Stop(); }

  // The worker's result, or nullopt with `failure` set when it crashed or hung.
  std::optional<CompileResult> Compile(const CompileRequest& request, std::string& failure) {
    std::error_code ec;
    const std::string job = Encode(Job{std::filesystem::current_path(ec).string(), request});
    bool sent = false;
    for (int attempt = 0; attempt < 2 && !sent; ++attempt) {  // a worker that died idle is replaced once
      if (fd_ < 0 && !Start()) break;
      sent = SendFrame(fd_, job);
      if (!sent) Stop();
    }
    if (!sent) {  // no worker process to be had: compile here, unprotected
      std::shared_lock lock(ForkGate());
      return CompileGuarded(request);
    }
    std::string reply;
    const Receive how = ReceiveFrame(fd_, reply, std::chrono::milliseconds(kWorkerTimeoutMs));
    CompileResult result;
    if (how == Receive::Ok && Decode(reply, result)) return result;
    failure = DescribeFailure(Stop(), how);
    return std::nullopt;
  }

 private:
  bool Start() {
    WarmUp();
    int fds[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) return false;
    {
      std::unique_lock lock(ForkGate());
      pid_ = fork();
    }
    if (pid_ == 0) WorkerMain(fds[1]);
    close(fds[1]);
    if (pid_ < 0) {
      close(fds[0]);
      return false;
    }
    fd_ = fds[0];
    return true;
  }

  // Ends the worker and returns its wait status.
  int Stop() {
    int status = 0;
    if (fd_ >= 0) close(fd_);
    if (pid_ > 0) {
      kill(pid_, SIGKILL);  // no-op when it already died; it holds no state worth a clean exit
      while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    }
    fd_ = -1;
    pid_ = -1;
    return status;
  }

  int fd_ = -1;
  pid_t pid_ = -1;
};

CompileResult CompileIsolated(const CompileRequest& request) {
  thread_local Worker worker;
  std::string failure;
  if (std::optional<CompileResult> result = worker.Compile(request, failure)) return std::move(*result);
  return ErrorResult(request, failure);
}

}  // namespace

Stage StageFromProfile(std::string_view profile, bool* valid) {
  static constexpr std::pair<std::string_view, Stage> kPrefixes[] = {
      {"vs_", Stage::Vertex},   {"hs_", Stage::Hull},  {"ds_", Stage::Domain},
      {"gs_", Stage::Geometry}, {"ps_", Stage::Pixel}, {"cs_", Stage::Compute},
  };
  const std::string_view version = profile.size() > 3 ? profile.substr(3) : std::string_view{};
  const bool sm5 = version == "5_0";
  const bool known = sm5 || version == "4_0" || version == "4_1";
  for (const auto& [prefix, stage] : kPrefixes) {
    if (!profile.starts_with(prefix)) continue;
    const bool tessellation = stage == Stage::Hull || stage == Stage::Domain;
    if (valid) *valid = known && (sm5 || !tessellation);
    return stage;
  }
  if (valid) *valid = false;
  return Stage::Vertex;
}

bool CrashIsolationAvailable() { return kCanFork; }

CompileResult CompileHlsl(const CompileRequest& request) {
  if (!request.isolate || !kCanFork) {
    std::shared_lock lock(ForkGate());
    return CompileGuarded(request);
  }
  try {
    return CompileIsolated(request);
  } catch (const std::exception& e) {  // e.g. std::bad_alloc encoding the request
    return ErrorResult(request, std::string("internal compiler error: ") + e.what());
  }
}

CompileResult CompileHlslFile(const std::string& path, const std::string& entryPoint, const std::string& profile,
                              const std::vector<std::string>& includeDirs) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    CompileResult result;
    result.errors.push_back({path, 0, 0, "cannot read the file"});
    return result;
  }
  std::ostringstream text;
  text << file.rdbuf();
  CompileRequest request;
  request.source = text.str();
  request.fileName = path;
  request.entryPoint = entryPoint;
  request.profile = profile;
  request.includeDirs = includeDirs;
  return CompileHlsl(request);
}

std::string CompileResult::FormatErrors() const {
  std::string out;
  for (const Diagnostic& d : errors) {
    std::string where = d.file;
    if (d.line > 0) where += ":" + std::to_string(d.line) + ":" + std::to_string(d.column);
    out += (where.empty() ? "" : where + ": ") + "error: " + d.message + "\n";
  }
  return out;
}

}  // namespace hlsl
