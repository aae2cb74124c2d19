#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "aaf/io/sequence.h"

namespace aaf::cli {

/// One unit of work of a command run over a sequence: one input frame, one output.
struct FrameJob {
    int frame = 0;  ///< frame number, 0 for a single file
    std::string input, output;
};

/// The frames of sequence pattern `pattern`: those of `frames` (a range spec;
/// a bad or empty one throws UsageError) or, when not given, those found on
/// disk (none throws InputError naming the pattern).
io::FrameRange sequence_frames(const std::string &pattern, const std::optional<std::string> &frames);

/// The jobs of a command, produced one at a time: `--frames 1-2000000000`
/// costs no more memory than one frame.
class FrameJobs {
  public:
    /// These jobs, as they are (a render's list, a single file).
    explicit FrameJobs(std::vector<FrameJob> jobs);
    /// One job per frame of `frames`: that frame's path of the `input` and of
    /// the `output` pattern.
    FrameJobs(std::string input, std::string output, io::FrameRange frames);
    /// An input that is the same file for every frame (a render's scene).
    struct FixedInput {
        std::string path;
    };
    static FixedInput fixed_input(std::string path) { return {std::move(path)}; }
    /// One job per frame of `frames`: `input` itself and that frame's path of the `output` pattern.
    FrameJobs(FixedInput input, std::string output, io::FrameRange frames);

    std::size_t size() const { return size_; }
    /// Calls `visit` with each job in order. A sequence job whose output is
    /// its input throws aaf::InputError before `visit` sees it.
    void for_each(const std::function<void(const FrameJob &)> &visit) const;

  private:
    std::vector<FrameJob> list_;
    std::string input_, output_;
    bool input_is_pattern_ = true;
    io::FrameRange frames_;
    std::size_t size_ = 0;
};

/// The jobs for `input` and `output`: both sequence patterns (shot.####.exr,
/// see io::frame_path) with the frames of `frames` (a range spec) or, when
/// not given, the input frames found on disk; or two plain files. Throws
/// UsageError for a pattern on one side only (a plain output would receive
/// every frame) or a bad range, aaf::InputError for an output that is the
/// input (of the first frame; later frames are checked as they come) or no frames.
FrameJobs frame_jobs(const std::string &input, const std::string &output,
                     const std::optional<std::string> &frames);

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
    bool skip_existing = false;  ///< skip frames whose output is up to date (`up_to_date`)
    /// With skip_existing: whether a job's output is complete and made from
    /// its inputs with these settings (provenance.h); unset, any output that
    /// reads back completely counts.
    std::function<bool(const FrameJob &)> up_to_date;
    bool skip_bad_frames = false;  ///< report a failed frame and go on (the exit code still says so)
};

/// Runs `work` on each job in order, one frame in memory at a time, and
/// reports progress. Returns the number of failed frames; without
/// skip_bad_frames the first failure is rethrown after reporting it.
std::size_t run_frames(const FrameJobs &jobs, const RunOptions &options,
                       const std::function<void(const FrameJob &)> &work);
inline std::size_t run_frames(const std::vector<FrameJob> &jobs, const RunOptions &options,
                              const std::function<void(const FrameJob &)> &work) {
    return run_frames(FrameJobs(jobs), options, work);
}

}  // namespace aaf::cli
