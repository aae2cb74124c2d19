#include "frame_runner.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <utility>

#include "aaf/core/util/error.h"
#include "aaf/io/atomic_file.h"
#include "aaf/io/exr_io.h"
#include "aaf/io/sequence.h"
#include "commands.h"

namespace aaf::cli {

namespace fs = std::filesystem;

io::FrameRange sequence_frames(const std::string &pattern, const std::optional<std::string> &frames) {
    io::FrameRange range;
    if (!frames)
        range = io::FrameRange::of(io::frames_on_disk(pattern));
    else if (frames->empty())
        throw UsageError("--frames: empty range (leave --frames out for every frame on disk)");
    else
        try {
            range = io::FrameRange::parse(*frames);
        } catch (const Error &e) {
            throw UsageError(std::string("--frames: ") + e.what());  // the command line's, not a file's
        }
    if (range.empty()) throw InputError(pattern + ": no frames found");
    return range;
}

FrameJobs::FrameJobs(std::vector<FrameJob> jobs) : list_(std::move(jobs)), size_(list_.size()) {}

FrameJobs::FrameJobs(std::string input, std::string output, io::FrameRange frames)
    : input_(std::move(input)),
      output_(std::move(output)),
      frames_(std::move(frames)),
      size_(frames_.size()) {}

FrameJobs::FrameJobs(FixedInput input, std::string output, io::FrameRange frames)
    : FrameJobs(std::move(input.path), std::move(output), std::move(frames)) {
    input_is_pattern_ = false;
}

void FrameJobs::for_each(const std::function<void(const FrameJob &)> &visit) const {
    for (const FrameJob &job : list_) visit(job);
    // Distinct frames give distinct paths of one pattern: no two jobs share an output.
    frames_.for_each([&](int frame) {
        const FrameJob job{frame, input_is_pattern_ ? io::frame_path(input_, frame) : input_,
                           io::frame_path(output_, frame)};
        io::check_not_same_file(job.input, job.output);
        visit(job);
    });
}

FrameJobs frame_jobs(const std::string &input, const std::string &output,
                     const std::optional<std::string> &frames) {
    const bool input_sequence = io::is_sequence_pattern(input),
               output_sequence = io::is_sequence_pattern(output);
    if (!input_sequence) {
        if (output_sequence) throw UsageError(output + ": a frame pattern needs an input pattern too");
        if (frames) throw UsageError("--frames needs sequence patterns (e.g. in.####.exr -o out.####.exr)");
        io::check_not_same_file(input, output);
        return FrameJobs({{0, input, output}});
    }
    if (!output_sequence)
        throw UsageError(output +
                         ": has no frame field (#, @ or %0Nd), so every frame would write this one file");
    io::FrameRange range = sequence_frames(input, frames);
    // The first frame is checked before anything runs (patterns that differ
    // only in spelling map every frame onto its input); the others as they come.
    io::check_not_same_file(io::frame_path(input, range.front()), io::frame_path(output, range.front()));
    return FrameJobs(input, output, std::move(range));
}

Progress progress_from_string(const std::string &name) {
    if (name == "auto") return Progress::Automatic;
    if (name == "lines") return Progress::Lines;
    if (name == "jsonl") return Progress::Jsonl;
    if (name == "openjd") return Progress::OpenJd;
    if (name == "none") return Progress::None;
    throw UsageError("unknown progress mode '" + name + "' (auto, lines, jsonl, openjd, none)");
}

std::size_t run_frames(const FrameJobs &jobs, const RunOptions &options,
                       const std::function<void(const FrameJob &)> &work) {
    using Clock = std::chrono::steady_clock;
    Progress mode = options.progress;
    if (mode == Progress::Automatic) mode = jobs.size() == 1 ? Progress::None : Progress::Lines;
    const bool bar =
        options.progress == Progress::Automatic && mode == Progress::Lines && ::isatty(STDERR_FILENO);
    const auto run_start = Clock::now();
    std::size_t done = 0, failed = 0, skipped = 0;
    if (mode == Progress::Jsonl)
        std::cout << nlohmann::json{{"event", "start"}, {"frames", jobs.size()}}.dump() << std::endl;
    const auto summary = [&](bool stopped) {
        if (mode != Progress::Jsonl) return;
        nlohmann::json event{{"event", "summary"},
                             {"frames", jobs.size()},
                             {"ok", done - failed - skipped},
                             {"failed", failed},
                             {"skipped", skipped},
                             {"seconds", std::chrono::duration<double>(Clock::now() - run_start).count()}};
        if (stopped) event["not_run"] = jobs.size() - done;  // a failed frame stopped the run
        std::cout << event.dump() << std::endl;
    };

    jobs.for_each([&](const FrameJob &job) {
        const auto start = Clock::now();
        std::string status = "ok", message;
        std::exception_ptr failure;
        if (options.skip_existing &&
            (options.up_to_date ? options.up_to_date(job) : io::is_readable_image(job.output))) {
            status = "skipped";
            ++skipped;
        } else {
            try {
                work(job);
            } catch (const std::exception &e) {
                status = "failed";
                message = e.what();
                failure = std::current_exception();
                ++failed;
                if (options.skip_bad_frames) std::cerr << "aaf: error: " << message << "\n";
            }
        }
        ++done;
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        if (mode == Progress::Jsonl) {
            nlohmann::json event{{"event", "frame_end"}, {"frame", job.frame}, {"input", job.input},
                                 {"output", job.output}, {"seconds", seconds}, {"status", status}};
            if (!message.empty()) event["error"] = message;
            std::cout << event.dump() << std::endl;
        } else if (mode == Progress::OpenJd) {
            std::cout << "openjd_progress: " << (100.0 * done / double(jobs.size())) << std::endl;
        } else if (bar) {
            const int width = 30, filled = int(width * done / double(jobs.size()));
            std::fprintf(stderr, "\r[%s%s] %zu/%zu frames", std::string(filled, '#').c_str(),
                         std::string(width - filled, ' ').c_str(), done, jobs.size());
            if (done == jobs.size() || (status == "failed" && !options.skip_bad_frames))
                std::fprintf(stderr, "\n");
        } else if (mode == Progress::Lines) {
            std::fprintf(stderr, "frame %d (%zu/%zu): %s -> %s: %s, %.2f s\n", job.frame, done, jobs.size(),
                         job.input.c_str(), job.output.c_str(), status.c_str(), seconds);
        }
        if (status == "failed" && !options.skip_bad_frames) {
            summary(/*stopped=*/true);
            std::rethrow_exception(failure);  // main prints it; its type sets the exit code
        }
    });
    summary(/*stopped=*/false);
    return failed;
}

}  // namespace aaf::cli
