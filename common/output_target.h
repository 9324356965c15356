// Checks on a file about to be written, made before any work: every writer goes through a
// temporary file and a rename, and a rename replaces whatever the name points at.
#pragma once

#include <string>
#include <vector>

namespace citygen {

// Throws citygen::Error (one line naming `path`) unless `path` is a new name or an existing
// regular file (not a symlink, directory, FIFO or device) in an existing writable directory,
// and is not the same file as any of `inputs`.
void check_output_target(const std::string& path, const std::vector<std::string>& inputs = {});

}  // namespace citygen
