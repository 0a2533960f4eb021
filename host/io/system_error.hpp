// clmesh — the text of a failed system call's errno, for the file readers' and writers' messages.
#pragma once

#include <cstring>
#include <string>

namespace clmesh {

inline std::string describe_errno(int error) {
  return error != 0 ? std::strerror(error) : "I/O error";
}

} // namespace clmesh
