#pragma once

#include <functional>
#include <optional>
#include <string>

namespace aaf::cli {

/// The history of a method that reads the previous frame's output
/// (`ratio --temporal`) over a sequence, kept independent of how the
/// sequence is cut into runs: frame f's history is frame f - 1's output,
/// back to the start of its sequence, whatever frames this run was asked
/// for. Before a frame is filtered, the frames its history needs and this
/// run has not just filtered are replayed (filtered in memory, not
/// written), so that a chunk, a resumed run and one uninterrupted run give
/// the same bytes; their identities are chained into the frame's
/// provenance.
class FrameHistory {
  public:
    struct Source {
        /// The first frame of the sequence `frame` belongs to (frame itself
        /// when it has no history), when it is known at once; else ...
        std::function<int(int frame)> sequence_start;
        /// ... whether frame - 1 belongs to `frame`'s sequence (its input is
        /// on disk): the start is found by walking back.
        std::function<bool(int frame)> continues;
        /// What `frame` adds to the outputs that depend on it, a hash
        /// (provenance.h's inputs_hash); `first` is true for the sequence's
        /// first frame, whose identity also says where the sequence starts.
        std::function<std::string(int frame, bool first)> identity;
        /// Filters `frame` in memory, its output becoming the pipeline's history.
        std::function<void(int frame)> replay;
        /// Empties the pipeline's history.
        std::function<void()> forget;
    };

    explicit FrameHistory(Source source) : source_(std::move(source)) {}

    /// The frames `frame`'s output depends on besides its own, "S-E", or
    /// "" at a sequence's start.
    std::string frames_read(int frame);
    /// The identities of frames start..`frame`, chained: changes when any of
    /// them changes (or when the sequence's start moves).
    std::string chain_hash(int frame);
    /// Makes the pipeline's history hold frame - 1's output (nothing at a
    /// sequence's start), replaying what this run has not filtered, before
    /// `frame` is filtered. A replay that fails throws its error, naming the
    /// frame.
    void prepare(int frame);
    /// After `frame` was filtered: its output is the history now. Until then
    /// (a frame that failed) the history counts as lost.
    void filtered(int frame) { held_ = frame; }

  private:
    int start_of(int frame);

    Source source_;
    std::optional<int> held_;                                ///< the frame whose output the pipeline holds
    std::optional<std::pair<int, int>> last_start_;          ///< (frame, its sequence start)
    std::optional<std::pair<int, std::string>> last_chain_;  ///< (frame, its chain hash)
};

}  // namespace aaf::cli
