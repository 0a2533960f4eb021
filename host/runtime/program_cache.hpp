// clmesh — on-disk cache of built OpenCL programs.
//
// Building a program from source costs the OpenCL compiler's front end on
// every run (PoCL preprocesses the source to look up its own cache, which is
// most of a small mesh's run). The cache keeps each
// device's binary (CL_PROGRAM_BINARIES) under a name that hashes everything
// the binary depends on, so a later run builds from the binary instead.
// Beside them it keeps results found with such a program (the predicate
// check's pass: Device::result_cache), keyed the same way.
//
// Best effort, never a failed run: an entry is handed to the driver only when
// its clmesh header checks out (magic, format version, the key it was stored
// for, payload size and checksum), because a driver may abort the process on
// a damaged binary (PoCL asserts on a truncated one). Anything else at the
// entry's name (missing, empty, truncated, garbage, a directory, unreadable)
// reads as no entry; the caller builds from source and stores the entry again,
// written aside under a name of its own and renamed over the old one, so that
// a reader sees the old entry or the new one, never half of one. A failed
// write leaves things as they were; the partial files of writers killed
// before their rename go with a later store, once an hour old.
//
// Location: $CLMESH_CACHE_DIR, else $XDG_CACHE_HOME/clmesh, else
// $HOME/.cache/clmesh; CLMESH_CACHE_DIR set to the empty string turns it off.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace clmesh {

class ProgramCache {
public:
  // `identity`: what besides the source decides the binary (build options,
  // platform, device and driver versions).
  ProgramCache(const std::string &source, const std::string &identity);

  // The binary stored for this key, or nothing when there is no valid entry.
  std::optional<std::vector<unsigned char>> load() const noexcept;
  // Replaces the entry with `binary`; errors are ignored.
  void store(const std::vector<unsigned char> &binary) const noexcept;

private:
  std::string path_;          // empty: no cache
  std::uint64_t key_[2] = {}; // the hash of (identity, source), also the file name
};

} // namespace clmesh
