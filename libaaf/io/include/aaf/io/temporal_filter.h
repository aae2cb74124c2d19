#pragma once

#include <memory>
#include <string>
#include <vector>

#include "aaf/core/framework/temporal_window.h"
#include "aaf/io/filter_file.h"

namespace aaf::io {

/// The frames of the sequence `pattern` that frame `frame`'s temporal
/// window reads, itself included, in order: those within the window whose
/// input is on disk, up to the first missing one on each side (the motion
/// that links them is followed frame to frame), and, unless causal, as many
/// after the frame as before it: centred, so that a steady change (a light
/// or a shadow moving at constant speed) averages to the frame's own value.
/// At a sequence's ends the window narrows to what exists on both sides;
/// which frames a run was asked for does not matter, so a chunk, a resumed
/// run and one uninterrupted run read the same.
std::vector<int> temporal_window_frames(const std::string &pattern, int frame,
                                        const TemporalWindowSettings &settings);

/// `filter` with a temporal window over the sequence `pattern`
/// (`aaf filter METHOD --temporal-window K`): running frame `*frame` (set
/// by the caller before each filter_file()) filters it as `filter` does,
/// its width inputs (MethodRoles::window_widths: AAF's occluder distances,
/// MAAF's wedges) first steadied to their extremes over the window
/// (temporal_window_extrema(); the output keeps the inputs as read), then blends the method's outputs (every
/// output role but its widths, and the beauty it composes) with those of
/// the frames temporal_window_frames() names, each filtered alone from its
/// own input (blend_temporal_window()). Neighbours are filtered once and
/// kept while the window still needs them; a method with width inputs
/// filters each frame twice (steadied, and alone for its neighbours). The
/// neighbours' outputs are the per-frame ones, never blended, so a frame's
/// bytes depend only on its window's inputs. `options` are those
/// the frames are read with (their beauty stays the filter's). Throws
/// aaf::InputError "<file>: ..." when a frame lacks the position, normal or
/// motion layers, and aaf::Error for a filter that reads its previous
/// output (a temporal filter of its own).
FrameFilter temporal_filter(FrameFilter filter, const std::string &pattern,
                            const TemporalWindowSettings &settings, const FilterFileOptions &options,
                            std::shared_ptr<const int> frame);

}  // namespace aaf::io
