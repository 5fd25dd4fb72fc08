#ifndef rbc_ifem_base_parameter_text_h
#define rbc_ifem_base_parameter_text_h

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Every parameter of @p prm as a .prm file: a first line naming the
   * program, its version and git commit (version_line()), then deal.II's
   * documented listing, each `set` line preceded by a line `# Allowed: ...`
   * that spells out the pattern the value is checked against. It reads back
   * as it is (ParameterHandler::parse_input_from_string()): what
   * --print-parameters prints and every run's parameters.prm holds.
   */
  std::string
  parameter_text(const ParameterHandler &prm);

  /// "Subsection/.../Entry" -> the description of its pattern, for every
  /// entry of @p prm.
  std::map<std::string, std::string>
  parameter_patterns(const ParameterHandler &prm);

  /**
   * "Subsection/.../Entry" -> its value, for every `set` line of a .prm
   * @p text (parameter_text()): what two runs' parameters.prm files are
   * compared by.
   */
  std::map<std::string, std::string>
  parameter_values(const std::string &text);

  /**
   * The values a pattern admits, in words, from deal.II's description of it
   * (PatternBase::description()): "[Double 0...MAX_DOUBLE (inclusive)]" is
   * "a number ≥ 0", "[Selection a|b ]" is "one of a | b", lists say their
   * length, separator and element. A description of another form is
   * returned as it is.
   */
  std::string
  allowed_values(const std::string &pattern_description);
} // namespace rbc_ifem

#endif
