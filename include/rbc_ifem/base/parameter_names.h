#ifndef rbc_ifem_base_parameter_names_h
#define rbc_ifem_base_parameter_names_h

#include <map>
#include <string>
#include <vector>

namespace rbc_ifem
{
  /**
   * The name of @p candidates nearest to @p name by edit distance (letters
   * compared without case), or "" when none is near enough to be a
   * misspelling: at most 2 edits, or a third of the longer name's
   * characters, whichever is more. What "did you mean" suggests.
   */
  std::string
  nearest_name(const std::string              &name,
               const std::vector<std::string> &candidates);

  /**
   * Throw InputError for the first `subsection` or `set` line of the .prm
   * @p text (read from @p filename) that names no subsection or entry that
   * @p patterns (parameter_patterns(): "Subsection/.../Entry" -> pattern)
   * declares: the message names the file, the line, the name, the nearest
   * declared name in that place ("did you mean 'X'?") and, for an entry
   * declared in another subsection, that subsection. Checked before deal.II
   * parses the file, whose own message names neither.
   */
  void
  check_parameter_names(const std::string                        &text,
                        const std::string                        &filename,
                        const std::map<std::string, std::string> &patterns);

  /**
   * The sentence an unknown parameter path "Subsection/.../Entry" (as
   * --set gives it) gets: the nearest declared path, or the subsection that
   * declares an entry of that name, or "" when there is nothing to suggest.
   */
  std::string
  suggest_parameter(const std::string                        &path,
                    const std::map<std::string, std::string> &patterns);
} // namespace rbc_ifem

#endif
