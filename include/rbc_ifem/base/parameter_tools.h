#ifndef rbc_ifem_base_parameter_tools_h
#define rbc_ifem_base_parameter_tools_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <string>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * ParameterHandler::add_parameter() (declare @p entry with the value of
   * @p value as its default, and bind @p value to it), checked: deal.II writes
   * the default as text with six significant digits and at once reads that
   * text back into @p value, so a default with more digits would change
   * silently. This refuses such a default with an error at start-up.
   */
  template <typename T>
  void
  add_parameter(ParameterHandler            &prm,
                const std::string           &entry,
                T                           &value,
                const std::string           &documentation,
                const Patterns::PatternBase &pattern =
                  *Patterns::Tools::Convert<T>::to_pattern())
  {
    const T default_value = value;
    prm.add_parameter(entry, value, documentation, pattern);
    AssertThrow(value == default_value,
                ExcMessage("the default of '" + entry +
                           "' has more than six significant digits"));
  }

  /**
   * The pattern of a number > 0 or the word auto, for a parameter that the
   * program can choose itself (Time/Time step).
   */
  class PositiveOrAuto : public Patterns::PatternBase
  {
  public:
    bool
    match(const std::string &text) const override;

    std::string
    description(const OutputStyle style = Machine) const override;

    std::unique_ptr<Patterns::PatternBase>
    clone() const override;
  };

  /**
   * The pattern of a number > @p lower, and ≤ @p upper if given: for a
   * parameter where the bound itself means nothing (a length or a modulus
   * of 0). deal.II's Patterns::Double includes its bounds; this keeps what
   * the allowed text says ("a number > 0") the same as what the program
   * accepts.
   */
  class GreaterThan : public Patterns::PatternBase
  {
  public:
    explicit GreaterThan(
      const double lower = 0.,
      const double upper = Patterns::Double::max_double_value);

    bool
    match(const std::string &text) const override;

    std::string
    description(const OutputStyle style = Machine) const override;

    std::unique_ptr<Patterns::PatternBase>
    clone() const override;

  private:
    double lower, upper;
  };

  /// "a|b|c" from @p names.
  inline std::string
  join_names(const std::vector<std::string> &names)
  {
    std::string text;
    for (const std::string &name : names)
      text += (text.empty() ? "" : "|") + name;
    return text;
  }

  /**
   * The names of the values of an enum, as a .prm file spells them: the one
   * place a choice such as Fluid/Model is written as text. Everything past
   * the parameter file works with the enum.
   */
  template <typename Enum>
  using SelectionNames = std::vector<std::pair<Enum, std::string>>;

  /// "a|b|c": the names for a Patterns::Selection.
  template <typename Enum>
  std::string
  selection_text(const SelectionNames<Enum> &names)
  {
    std::vector<std::string> text;
    for (const auto &[value, name] : names)
      text.push_back(name);
    return join_names(text);
  }

  template <typename Enum>
  const std::string &
  name_of(const Enum value, const SelectionNames<Enum> &names)
  {
    for (const auto &[v, name] : names)
      if (v == value)
        return name;
    Assert(false, ExcInternalError());
    return names.front().second;
  }

  /// The value named @p name; the Selection pattern has checked the name.
  template <typename Enum>
  Enum
  value_of(const std::string &name, const SelectionNames<Enum> &names)
  {
    for (const auto &[value, n] : names)
      if (n == name)
        return value;
    AssertThrow(false, ExcMessage("no value is named '" + name + "'"));
    return names.front().first;
  }

  /**
   * Declare @p entry as a selection of @p names whose default is the name of
   * @p value, and bind @p value to it (as ParameterHandler::add_parameter()
   * does for numbers).
   */
  template <typename Enum>
  void
  add_selection(ParameterHandler           &prm,
                const std::string          &entry,
                Enum                       &value,
                const SelectionNames<Enum> &names,
                const std::string          &documentation)
  {
    prm.declare_entry(entry,
                      name_of(value, names),
                      Patterns::Selection(selection_text(names)),
                      documentation);
    prm.add_action(entry, [&value, names](const std::string &name) {
      value = value_of(name, names);
    });
  }

  /// The same for a comma-separated list of at least one name.
  template <typename Enum>
  void
  add_selection(ParameterHandler           &prm,
                const std::string          &entry,
                std::vector<Enum>          &values,
                const SelectionNames<Enum> &names,
                const std::string          &documentation)
  {
    std::string defaults;
    for (const Enum value : values)
      defaults += (defaults.empty() ? "" : ", ") + name_of(value, names);
    prm.declare_entry(entry,
                      defaults,
                      Patterns::List(Patterns::Selection(selection_text(names)),
                                     1),
                      documentation);
    prm.add_action(entry, [&values, names](const std::string &list) {
      values.clear();
      for (const std::string &name : Utilities::split_string_list(list))
        values.push_back(value_of(name, names));
    });
  }
} // namespace rbc_ifem

#endif
