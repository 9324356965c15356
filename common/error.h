// The one exception type for user-facing failures: its message is the single line the
// programs print on stderr before exiting non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace citygen {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace citygen
