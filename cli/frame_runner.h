#pragma once

#include <functional>
#include <string>
#include <vector>

namespace aaf::cli {

/// One unit of work of a command run over a sequence: one input frame, one output.
struct FrameJob {
    int frame = 0;  ///< frame number, 0 for a single file
    std::string input, output;
};

/// The frames of sequence pattern `pattern`: those of `frames` (a range spec;
/// a bad one throws UsageError) or, when empty, those found on disk (none
/// throws InputError naming the pattern).
std::vector<int> sequence_frames(const std::string &pattern, const std::string &frames);

/// The jobs for `input` and `output`: both sequence patterns (shot.####.exr,
/// see io::frame_path) with the frames of `frames` (a range spec) or, when
/// empty, the input frames found on disk; or two plain files. Throws
/// aaf::Error for a pattern on one side only (a plain output would receive
/// every frame), an output that maps to an input, or no frames.
std::vector<FrameJob> frame_jobs(const std::string &input, const std::string &output,
                                 const std::string &frames);

/// How progress is reported.
enum class Progress {
    Automatic,  ///< a bar on a terminal, else one line per frame (stderr); silent for one file
    Lines,      ///< one line per frame on stderr
    Jsonl,      ///< one JSON object per event on stdout: start, frame_end, summary
    OpenJd,     ///< `openjd_progress: <percent>` lines on stdout (Open Job Description)
    None,
};
Progress progress_from_string(const std::string &name);

struct RunOptions {
    Progress progress = Progress::Automatic;
    bool skip_existing = false;    ///< skip frames whose output exists and whose header reads back
    bool skip_bad_frames = false;  ///< report a failed frame and go on (the exit code still says so)
};

/// Runs `work` on each job in order, one frame in memory at a time, and
/// reports progress. Returns the number of failed frames; without
/// skip_bad_frames the first failure is rethrown after reporting it.
int run_frames(const std::vector<FrameJob> &jobs, const RunOptions &options,
               const std::function<void(const FrameJob &)> &work);

}  // namespace aaf::cli
