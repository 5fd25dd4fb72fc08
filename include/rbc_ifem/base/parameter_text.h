#ifndef rbc_ifem_base_parameter_text_h
#define rbc_ifem_base_parameter_text_h

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <vector>

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
   * One line of a .prm text as deal.II reads it: what it is, the entry or
   * subsection it names, and the subsections it lies in. What every reader
   * of a .prm text here walks, so that each follows the subsections alike.
   */
  struct ParameterLine
  {
    enum class Kind
    {
      set,
      subsection,
      end,
      other
    };
    Kind kind;
    /// The entry of a `set` line, the subsection of a `subsection` line.
    std::string name;
    /// A `set` line's value, up to a comment, without blanks at its ends.
    std::string value;
    /// The subsections around the line, "A/B/" ("" at the top level).
    std::string prefix;
    /// The line's number, from 1, and the line as written.
    unsigned int number;
    std::string  text;
  };

  /// Every line of a .prm @p text.
  std::vector<ParameterLine>
  parameter_lines(const std::string &text);

  /**
   * Set the entry @p path ("Subsection/.../Entry") of @p prm to @p value
   * (ParameterHandler::set(), which checks the value against the entry's
   * pattern and throws deal.II's exception if it does not match).
   */
  void
  set_entry(ParameterHandler  &prm,
            const std::string &path,
            const std::string &value);

  /// One `set` line of a .prm text: "Subsection/.../Entry", the value, and
  /// the line's number (from 1).
  struct ParameterEntry
  {
    std::string  path;
    std::string  value;
    unsigned int line;
  };

  /// Every `set` line of a .prm @p text, in order.
  std::vector<ParameterEntry>
  parameter_entries(const std::string &text);

  /**
   * The text of the parameter file @p filename as ParameterHandler is to
   * read it: without a UTF-8 byte-order mark at its start. Adds to
   * @p warnings a line for each entry set twice in the same subsection (the
   * later value counts), and one if the file sets nothing.
   */
  std::string
  read_parameter_file(const std::string        &filename,
                      std::vector<std::string> &warnings);

  /**
   * Throw InputError naming the first real-valued entry of @p prm (not a
   * name, a switch or a whole number) with a number of magnitude below
   * 1e-15 or above 1e15 (other than 0), or not finite: no physical value in our
   * units (µm, s, pN) lies there, and such a number overflows or vanishes in
   * the solvers.
   */
  void
  check_magnitudes(const ParameterHandler &prm);

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
