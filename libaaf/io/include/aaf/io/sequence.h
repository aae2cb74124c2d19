#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace aaf::io {

// A thin layer over OpenImageIO's Filesystem sequence functions
// (parse_pattern, enumerate_sequence, enumerate_file_sequence,
// scan_for_matching_filenames) with two rules of its own: ':' is a step like
// 'x' (OIIO ignores it), and n '#' mean n digits (OIIO: one '#' = 4 digits).

/// The frame numbers of a range spec, held as its items and produced one at a
/// time: "1-2000000000" takes a few bytes, not 8 GB. Frames come in the order
/// written, a frame that an earlier item already gave is skipped.
class FrameRange {
  public:
    /// One item of a spec: first, first + step, ... up to last (inclusive).
    struct Item {
        int first = 0, last = 0, step = 1;
    };

    /// Parses "7"; "1-100"; "1-100x2" or "1-100:2" (every 2nd frame from 1);
    /// lists of these separated by commas, "1,5,7-9". Throws aaf::Error on an
    /// empty or malformed spec, a number outside the int range, a zero or
    /// negative step, or an end before its start.
    static FrameRange parse(const std::string &spec);
    /// The frames of `frames`, in that order (duplicates skipped).
    static FrameRange of(const std::vector<int> &frames);

    /// The number of distinct frames. O(items) when the items' spans do not
    /// overlap (the usual case); otherwise it counts them one by one.
    std::size_t size() const;
    bool empty() const { return items_.empty(); }
    /// True when `frame` is one of the range's frames; O(items).
    bool contains(int frame) const;
    /// The first frame; the range must not be empty.
    int front() const { return items_.front().first; }

    /// Calls `visit` with each frame in order; O(1) memory whatever the size.
    template <typename Visit>
    void for_each(const Visit &visit) const {
        for (std::size_t i = 0; i < items_.size(); ++i)
            // 64-bit: `frame + step` may pass INT_MAX at the end of an item.
            for (long long frame = items_[i].first; frame <= items_[i].last; frame += items_[i].step)
                if (disjoint_ || !given_before(i, int(frame))) visit(int(frame));
    }

    /// Every frame in a vector (for short ranges only).
    std::vector<int> to_vector() const;

  private:
    /// True when an item before `item` already gives `frame`.
    bool given_before(std::size_t item, int frame) const;

    std::vector<Item> items_;
    bool disjoint_ = true;  ///< no two items' [first, last] spans overlap: no duplicates possible
};

/// True when `path` names a sequence: a run of `#` or `@`, or a printf
/// `%d` / `%0Nd` field.
bool is_sequence_pattern(const std::string &path);

/// The path of one frame. Padding rule (as Blender, not oiiotool): a run of n
/// `#` (or `@`) is the frame number zero-padded to n digits, so
/// `shot.####.exr` is `shot.0007.exr`; `%04d` pads to 4, `%d` does not pad.
/// Negative frames keep their sign before the padding. Throws aaf::Error when
/// the pattern has no frame field.
std::string frame_path(const std::string &pattern, int frame);

/// Frames of `pattern` that exist on disk, ascending: the directory is listed
/// once and names are matched against the pattern.
std::vector<int> frames_on_disk(const std::string &pattern);

}  // namespace aaf::io
