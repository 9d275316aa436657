#include "daep/eval/BenchmarkRunner.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "daep/common/BuildInfo.h"
#include "daep/eval/BenchmarkResults.h"
#include "daep/eval/CpuLoad.h"

extern char** environ;

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace daep::eval {

namespace {

/** Exit code that marks a run stopped by the user: it stays pending. */
constexpr int kInterruptedExit = 130;

volatile std::sig_atomic_t gInterrupts = 0;

void onInterrupt(int) {
    gInterrupts = gInterrupts + 1;
}

/** Installs the SIGINT/SIGTERM handler for the lifetime of the object (no SA_RESTART). */
class InterruptGuard {
public:
    InterruptGuard() {
        gInterrupts = 0;
        struct sigaction sa {};
        sa.sa_handler = onInterrupt;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGINT, &sa, &oldInt_);
        sigaction(SIGTERM, &sa, &oldTerm_);
    }
    ~InterruptGuard() {
        sigaction(SIGINT, &oldInt_, nullptr);
        sigaction(SIGTERM, &oldTerm_, nullptr);
    }
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    struct sigaction oldInt_ {};
    struct sigaction oldTerm_ {};
};

std::string clockText(double seconds) {
    const long s = static_cast<long>(seconds + 0.5);
    char buf[32];
    if (s >= 3600)
        std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    return buf;
}

int readExitCode(const fs::path& dir) {
    std::ifstream in(dir / kExitCodeFile);
    int code = -1;
    if (!(in >> code))
        return -1;
    return code;
}

void writeExitCode(const fs::path& dir, int code) {
    std::ofstream(dir / kExitCodeFile) << code << "\n";
}

int exitCodeOf(int status) {
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 255;
}

/** Starts the binary with stdout+stderr into `log`, stdin from /dev/null, in its own group. */
pid_t spawn(const std::string& binary, const std::vector<std::string>& args,
            const std::string& log) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(binary.c_str()));
    for (const auto& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    // Own process group: a Ctrl-C reaches the runner only, which then decides what to forward.
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attr, 0);
    pid_t pid = -1;
    const int err = posix_spawn(&pid, binary.c_str(), &actions, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    if (err != 0)
        throw std::runtime_error("cannot start " + binary + ": " + std::strerror(err));
    return pid;
}

/** Bookkeeping of one invocation, and the progress display. */
class Progress {
public:
    Progress(std::ostream& out, bool interactive, std::size_t total, std::size_t alreadyDone,
             std::size_t alreadyFailed, int jobs)
        : out_(out),
          interactive_(interactive),
          total_(total),
          done_(alreadyDone),
          failed_(alreadyFailed),
          jobs_(jobs) {}

    void finished(const std::string& id, double seconds, bool ok, const std::string& detail,
                  std::size_t running, std::size_t notStarted) {
        running_ = running;
        notStarted_ = notStarted;
        ++done_;
        failed_ += ok ? 0 : 1;
        durations_ += seconds;
        ++timed_;
        if (interactive_ && !ok)
            out_ << "\r\x1b[K";
        if (!interactive_ || !ok)
            out_ << (ok ? "done   " : "FAILED ") << id << " (" << clockText(seconds) << ")"
                 << (detail.empty() ? "" : ", " + detail) << "  [" << done_ << "/" << total_
                 << ", failed " << failed_ << ", ETA " << eta() << "]" << std::endl;
        draw();
    }

    void update(std::size_t running, std::size_t notStarted) {
        running_ = running;
        notStarted_ = notStarted;
        draw();
    }

    void finish() {
        if (interactive_)
            out_ << "\n";
        out_.flush();
    }

private:
    std::string eta() const {
        if (timed_ == 0)
            return "--:--";
        const double left = static_cast<double>(notStarted_ + running_);
        return clockText(durations_ / timed_ * left / jobs_);
    }

    void draw() {
        if (!interactive_)
            return;
        constexpr int width = 30;
        const int filled = total_ ? static_cast<int>(width * done_ / total_) : width;
        const double elapsed = std::chrono::duration<double>(Clock::now() - begin_).count();
        out_ << "\r\x1b[K[" << std::string(filled, '#') << std::string(width - filled, '.') << "] "
             << done_ << "/" << total_ << "  failed " << failed_ << "  running " << running_
             << "  elapsed " << clockText(elapsed) << "  ETA " << eta() << std::flush;
    }

    std::ostream& out_;
    bool interactive_;
    std::size_t total_, done_, failed_;
    int jobs_;
    std::size_t running_ = 0, notStarted_ = 0;
    double durations_ = 0.0;
    std::size_t timed_ = 0;
    Clock::time_point begin_ = Clock::now();
};

std::string fileText(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/** `[section] key` -> value of an ini text (as config.ini: one `key = value` per line). */
std::map<std::string, std::string> iniValues(const std::string& text) {
    std::map<std::string, std::string> values;
    std::istringstream in(text);
    std::string line, section;
    while (std::getline(in, line)) {
        if (line.size() > 1 && line.front() == '[' && line.back() == ']') {
            section = line;
            continue;
        }
        const auto eq = line.find(" = ");
        if (eq != std::string::npos)
            values[section + " " + line.substr(0, eq)] = line.substr(eq + 3);
    }
    return values;
}

std::string describeParameterChanges(const std::string& before, const std::string& now) {
    const auto old = iniValues(before);
    const auto current = iniValues(now);
    std::vector<std::string> changes;
    for (const auto& [key, value] : current) {
        const auto it = old.find(key);
        if (it == old.end())
            changes.push_back(key + " added (" + value + ")");
        else if (it->second != value)
            changes.push_back(key + ": " + it->second + " -> " + value);
    }
    for (const auto& [key, value] : old)
        if (!current.count(key))
            changes.push_back(key + " removed");
    constexpr std::size_t kShown = 4;
    std::string text;
    for (std::size_t i = 0; i < changes.size() && i < kShown; ++i)
        text += (i ? "; " : "") + changes[i];
    if (changes.size() > kShown)
        text += "; and " + std::to_string(changes.size() - kShown) + " more";
    return text;
}

std::string describeFileChanges(const RunInputs& before, const RunInputs& now) {
    std::string text;
    for (const auto& file : now.files) {  // no structured binding: clang 14 cannot capture one
        const auto it = std::find_if(before.files.begin(), before.files.end(),
                                     [&file](const auto& f) { return f.first == file.first; });
        if (it == before.files.end() || it->second != file.second)
            text += (text.empty() ? "" : ", ") + file.first;
    }
    return text.empty() ? "" : "world file " + text + " changed";
}

}  // namespace

std::string shellQuote(const std::string& word) {
    if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWX"
                                                "YZ0123456789_-+./=:,@%") == std::string::npos)
        return word;
    std::string out = "'";
    for (char c : word)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

BenchmarkRunner::BenchmarkRunner(BenchmarkConfig config, RunnerOptions options,
                                 std::vector<RunSpec> runs)
    : config_(std::move(config)), options_(std::move(options)), runs_(std::move(runs)) {
    if (runs_.empty())
        runs_ = config_.expand();
    options_.outDirectory = fs::absolute(options_.outDirectory).lexically_normal().string();
    options_.exploreBinary = fs::absolute(options_.exploreBinary).lexically_normal().string();
    if (options_.jobs < 1)
        options_.jobs = 1;
}

std::string BenchmarkRunner::runDirectory(const RunSpec& run) const {
    return (fs::path(options_.outDirectory) / "runs" / run.id()).string();
}

std::vector<std::string> BenchmarkRunner::arguments(const RunSpec& run) const {
    std::vector<std::string> args{config_.experiment};
    for (const auto& assignment : config_.runOverrides(run))
        args.insert(args.end(), {"--set", assignment});
    args.insert(args.end(), {"--out", runDirectory(run), "--quiet"});
    return args;
}

bool BenchmarkRunner::isDone(const RunSpec& run) const {
    const fs::path dir = runDirectory(run);
    if (!changeSinceLastRun(run).empty())
        return false;
    const int code = readExitCode(dir);
    if (code == 0)
        return fs::exists(dir / "summary.json");
    return code > 0 && code != kInterruptedExit && !options_.retryFailed;
}

std::string BenchmarkRunner::changeSinceLastRun(const RunSpec& run) const {
    const fs::path dir = runDirectory(run);
    if (run.inputs.digest.empty() || !fs::exists(dir / kRunSpecFile))
        return "";
    RunInputs before;
    try {
        before = readRun(dir.string()).spec.inputs;
    } catch (const std::exception&) {
        return "its run.json is unreadable";
    }
    if (before.digest == run.inputs.digest)
        return "";
    if (before.digest.empty())
        return "it ran without a parameter digest (an older daep-benchmark)";
    const fs::path config = dir / "config.ini";
    std::string what =
        fs::exists(config) ? describeParameterChanges(fileText(config), run.inputs.parameters) : "";
    const std::string files = describeFileChanges(before, run.inputs);
    if (!files.empty())
        what += (what.empty() ? "" : "; ") + files;
    return what.empty() ? "its parameters changed" : what;
}

void BenchmarkRunner::reportResumeDecisions(std::ostream& out) const {
    const std::string thisBuild = buildInfo().version + " " + shortCommit();
    for (const auto& run : runs_) {
        const std::string change = changeSinceLastRun(run);
        if (!change.empty()) {
            out << "re-run  " << run.id() << ": " << change << "\n";
            continue;
        }
        if (!isDone(run))
            continue;
        const std::string madeBy = readRun(runDirectory(run)).build();
        if (!madeBy.empty() && madeBy != thisBuild)
            out << "kept    " << run.id() << ": parameters unchanged, made by build " << madeBy
                << " (this is " << thisBuild << ")\n";
    }
}

std::vector<RunSpec> BenchmarkRunner::pendingRuns() const {
    std::vector<RunSpec> pending;
    for (const auto& run : runs_)
        if (!isDone(run))
            pending.push_back(run);
    return pending;
}

RunnerReport BenchmarkRunner::run(std::ostream& progressOut) {
    const auto& all = runs_;
    reportResumeDecisions(progressOut);
    const auto pending = pendingRuns();
    RunnerReport report;
    report.total = all.size();
    report.skipped = all.size() - pending.size();
    std::size_t& failedBefore = report.failedBefore;
    for (const auto& r : all)
        if (readExitCode(runDirectory(r)) > 0 && isDone(r))
            ++failedBefore;
    if (report.skipped > 0)
        progressOut << report.skipped << " of " << all.size() << " runs already done or failed"
                    << (failedBefore ? " (" + std::to_string(failedBefore) +
                                           " failed; --retry-failed re-runs them)"
                                     : "")
                    << "\n";

    struct Running {
        RunSpec spec;
        Clock::time_point begin;
    };
    std::map<pid_t, Running> running;
    Progress progress(progressOut, options_.interactive, all.size(), report.skipped, failedBefore,
                      options_.jobs);
    InterruptGuard guard;
    const CpuLoad load(options_.loadThreads);
    std::size_t next = 0;
    int handledInterrupts = 0;
    auto lastDraw = Clock::now();

    while (true) {
        while (gInterrupts == 0 && running.size() < static_cast<std::size_t>(options_.jobs) &&
               next < pending.size()) {
            const RunSpec& spec = pending[next++];
            const fs::path dir = runDirectory(spec);
            writeRunSpec(dir.string(), spec, options_.loadThreads);
            fs::remove(dir / kExitCodeFile);
            fs::remove(dir / "summary.json");
            try {
                const pid_t pid =
                    spawn(options_.exploreBinary, arguments(spec), (dir / kRunLogFile).string());
                running[pid] = {spec, Clock::now()};
            } catch (const std::runtime_error& e) {
                // Recorded like a shell's "command not executable" so the batch carries on.
                std::ofstream(dir / kRunLogFile) << e.what() << "\n";
                writeExitCode(dir, 127);
                ++report.failed;
                progress.finished(spec.id(), 0.0, false, e.what(), running.size(),
                                  pending.size() - next);
            }
            progress.update(running.size(), pending.size() - next);
        }
        if (running.empty())
            break;

        if (gInterrupts != handledInterrupts) {
            handledInterrupts = gInterrupts;
            report.interrupted = true;
            const int sig = handledInterrupts == 1 ? SIGINT : SIGKILL;
            if (options_.interactive)
                progressOut << "\r\x1b[K";
            progressOut << (sig == SIGINT ? "interrupted: stopping the running missions (Ctrl-C "
                                            "again kills them)\n"
                                          : "killing the running missions\n");
            for (const auto& [pid, r] : running)
                ::kill(pid, sig);
        }

        int status = 0;
        const pid_t pid = ::waitpid(-1, &status, WNOHANG);
        if (pid <= 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            if (Clock::now() - lastDraw > std::chrono::milliseconds(500)) {
                progress.update(running.size(), pending.size() - next);
                lastDraw = Clock::now();
            }
            continue;
        }
        const auto it = running.find(pid);
        if (it == running.end())
            continue;
        const Running r = it->second;
        running.erase(it);
        const fs::path dir = runDirectory(r.spec);
        const double seconds = std::chrono::duration<double>(Clock::now() - r.begin).count();
        int code = exitCodeOf(status);
        if (report.interrupted && code != 0)
            code = kInterruptedExit;
        writeExitCode(dir, code);
        if (code == kInterruptedExit) {
            progress.update(running.size(), pending.size() - next);
            continue;
        }
        const bool ok = code == 0 && fs::exists(dir / "summary.json");
        ok ? ++report.succeeded : ++report.failed;
        std::string detail;
        if (!ok)
            detail = (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                          : "exit " + std::to_string(code)) +
                     ", log " + (dir / kRunLogFile).string();
        progress.finished(r.spec.id(), seconds, ok, detail, running.size(), pending.size() - next);
    }
    progress.finish();
    return report;
}

std::size_t BenchmarkRunner::emitJobs(const std::string& path) const {
    std::ofstream out(path);
    if (!out)
        throw std::runtime_error("cannot write " + path);
    std::size_t count = 0;
    for (const auto& spec : pendingRuns()) {
        const fs::path dir = runDirectory(spec);
        writeRunSpec(dir.string(), spec);
        // Results made with other inputs must not pass for this run's before the job runs.
        fs::remove(dir / kExitCodeFile);
        fs::remove(dir / "summary.json");
        const std::string d = shellQuote(dir.string());
        out << "mkdir -p " << d << " && rm -f " << shellQuote((dir / kExitCodeFile).string()) << ' '
            << shellQuote((dir / "summary.json").string()) << " && "
            << shellQuote(options_.exploreBinary);
        for (const auto& a : arguments(spec))
            out << ' ' << shellQuote(a);
        out << " > " << shellQuote((dir / kRunLogFile).string()) << " 2>&1; echo $? > "
            << shellQuote((dir / kExitCodeFile).string()) << '\n';
        ++count;
    }
    if (!out)
        throw std::runtime_error("cannot write " + path);
    return count;
}

}  // namespace daep::eval
