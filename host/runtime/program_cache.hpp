// clmesh — on-disk cache of built OpenCL programs.
//
// Building a program from source costs the OpenCL compiler's front end on
// every run (PoCL preprocesses the source to look up its own cache, which is
// most of a small mesh's run). The cache keeps each
// device's binary (CL_PROGRAM_BINARIES) under a name that hashes everything
// the binary depends on, so a later run builds from the binary instead.
// Best effort: a missing, unreadable or rejected entry means a source build,
// and a failed write is ignored.
//
// Location: $CLMESH_CACHE_DIR, else $XDG_CACHE_HOME/clmesh, else
// $HOME/.cache/clmesh; CLMESH_CACHE_DIR set to the empty string turns it off.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace clmesh {

class ProgramCache {
public:
  // `identity`: what besides the source decides the binary (build options,
  // platform, device and driver versions).
  ProgramCache(const std::string &source, const std::string &identity);

  std::optional<std::vector<unsigned char>> load() const;
  void store(const std::vector<unsigned char> &binary) const;

private:
  std::string path_; // empty: no cache
};

} // namespace clmesh
