#ifndef rbc_ifem_base_version_h
#define rbc_ifem_base_version_h

#include <string>

namespace rbc_ifem
{
  /// The release, as in CMakeLists.txt's project(VERSION), e.g. "0.9.0".
  std::string
  version();

  /**
   * The git commit the program was built from (git describe: the short hash,
   * "-dirty" if the work tree had uncommitted changes), or "unknown" when it
   * was built outside a git clone.
   */
  std::string
  git_commit();

  /// "rbc-ifem 0.9.0 (git 1a2b3c4d5e6f)": what --version, the log and
  /// parameters.prm say.
  inline std::string
  version_line()
  {
    return "rbc-ifem " + version() + " (git " + git_commit() + ")";
  }
} // namespace rbc_ifem

#endif
