#include "common/output_target.h"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"

namespace citygen {

namespace {

std::string directory_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

}  // namespace

void check_output_target(const std::string& path, const std::vector<std::string>& inputs) {
    if (path.empty()) throw Error("empty output file name");
    if (path.back() == '/') throw Error(path + ": cannot write: a directory name, not a file name");
    struct stat target;
    if (::lstat(path.c_str(), &target) == 0) {
        if (S_ISLNK(target.st_mode))
            throw Error(path + ": cannot write: a symbolic link; refusing to replace it (name the file it points to)");
        if (!S_ISREG(target.st_mode))
            throw Error(path + ": cannot write: exists and is not a regular file (a directory, device or pipe); refusing to replace it");
        for (const std::string& input : inputs) {
            struct stat in;
            if (!input.empty() && ::stat(input.c_str(), &in) == 0 && in.st_dev == target.st_dev &&
                in.st_ino == target.st_ino)
                throw Error(path + ": cannot write: the same file as the input " + input + "; refusing to overwrite the input");
        }
    } else if (errno != ENOENT) {
        throw Error(path + ": cannot write (" + std::strerror(errno) + ")");
    }
    const std::string dir = directory_of(path);
    struct stat info;
    if (::stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
        throw Error(path + ": cannot write (directory " + dir + " does not exist)");
    if (::access(dir.c_str(), W_OK) != 0) throw Error(path + ": cannot write (directory " + dir + " is not writable)");
}

}  // namespace citygen
