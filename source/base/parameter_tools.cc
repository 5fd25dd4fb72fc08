#include <rbc_ifem/base/parameter_tools.h>

#include <cmath>
#include <exception>
#include <memory>
#include <sstream>

namespace rbc_ifem
{
  bool
  PositiveOrAuto::match(const std::string &text) const
  {
    return Utilities::trim(text) == "auto" || GreaterThan().match(text);
  }

  std::string
  PositiveOrAuto::description(const OutputStyle) const
  {
    return "[a number > 0, or auto]";
  }

  std::unique_ptr<Patterns::PatternBase>
  PositiveOrAuto::clone() const
  {
    return std::make_unique<PositiveOrAuto>();
  }

  GreaterThan::GreaterThan(const double lower, const double upper)
    : lower(lower)
    , upper(upper)
  {}

  bool
  GreaterThan::match(const std::string &text) const
  {
    try
      {
        std::size_t  end   = 0;
        const double value = std::stod(text, &end);
        return value > lower && value <= upper && std::isfinite(value) &&
               Utilities::trim(text.substr(end)).empty();
      }
    catch (const std::exception &)
      {
        return false;
      }
  }

  std::string
  GreaterThan::description(const OutputStyle) const
  {
    std::ostringstream text;
    text << "[a number > " << lower;
    if (upper < Patterns::Double::max_double_value)
      text << " and ≤ " << upper;
    text << "]";
    return text.str();
  }

  std::unique_ptr<Patterns::PatternBase>
  GreaterThan::clone() const
  {
    return std::make_unique<GreaterThan>(lower, upper);
  }
} // namespace rbc_ifem
