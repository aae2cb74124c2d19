#include "frame_history.h"

#include <climits>

#include "aaf/core/util/error.h"
#include "provenance.h"

namespace aaf::cli {

int FrameHistory::start_of(int frame) {
    if (source_.sequence_start) return source_.sequence_start(frame);
    if (last_start_ && last_start_->first == frame) return last_start_->second;
    // Frames are mostly asked for in order: frame - 1's start is frame's when frame continues it.
    int start = frame;
    while (start > INT_MIN && source_.continues(start)) {
        if (last_start_ && last_start_->first == start - 1) {
            start = last_start_->second;
            break;
        }
        --start;
    }
    last_start_ = {frame, start};
    return start;
}

std::string FrameHistory::frames_read(int frame) {
    const int start = start_of(frame);
    if (start == frame) return "";
    return std::to_string(start) + "-" + std::to_string(frame - 1);
}

std::string FrameHistory::chain_hash(int frame) {
    if (last_chain_ && last_chain_->first == frame)
        return last_chain_->second;  // asked again (--skip-existing)
    const int start = start_of(frame);
    int from = start;
    std::string chain;
    if (last_chain_ && last_chain_->first >= start && last_chain_->first < frame) {
        from = last_chain_->first + 1;
        chain = last_chain_->second;
    }
    for (int g = from;; ++g) {
        // Each link hashes the chain so far with the frame's own identity.
        chain = inputs_hash({}, chain + "|" + source_.identity(g, g == start));
        if (g == frame) break;
    }
    last_chain_ = {frame, chain};
    return chain;
}

void FrameHistory::prepare(int frame) {
    const int start = start_of(frame);
    if (start == frame) {
        source_.forget();
        held_.reset();
        return;
    }
    if (held_ && *held_ == frame - 1) {
        held_.reset();  // frame's filter changes it
        return;
    }
    int from = start;
    if (held_ && *held_ >= start && *held_ < frame)
        from = *held_ + 1;  // the history already reaches that far
    else
        source_.forget();
    held_.reset();
    for (int g = from; g < frame; ++g) {
        try {
            with_context("frame " + std::to_string(frame) + "'s history needs frame " + std::to_string(g),
                         [&] { source_.replay(g); });
        } catch (...) {
            source_.forget();  // a half-made history must not reach a later frame
            held_.reset();
            throw;
        }
        held_ = g;
    }
    held_.reset();  // frame's filter changes it
}

}  // namespace aaf::cli
