#pragma once
/// @file
/// A file written whole or not at all: the content goes to `<path>.tmp`, which is flushed to
/// the disk and renamed over `path`; then the directory is flushed, so that the rename too
/// survives a power cut (best effort: the file is in place either way). On failure the
/// temporary file is removed and `path` is left as it was. Saved maps, merged clouds and
/// swliod's kept time offset are written through it.

#include <functional>
#include <ostream>
#include <string>

namespace swlio::estimator {

/// `write` fills the stream; it returns false, with `*why` set, to give up. `*error` (may be
/// null) then holds `why`, or the step that failed with `what` in front ("map write: renaming
/// a.tmp to a failed: …").
bool ReplaceFile(const std::string& path,
                 const std::string& what,
                 const std::function<bool(std::ostream& out, std::string* why)>& write,
                 std::string* error);

}  // namespace swlio::estimator
