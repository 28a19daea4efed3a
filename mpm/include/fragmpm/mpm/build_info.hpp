#pragma once
// Program version and git hash, from a source file CMake generates at configure time, so that a new
// commit recompiles one file instead of every file that sees a compile definition.
namespace fragmpm::mpm {

const char* program_version();
const char* program_git_hash();

}  // namespace fragmpm::mpm
