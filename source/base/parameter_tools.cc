#include <rbc_ifem/base/parameter_tools.h>

#include <cmath>
#include <exception>
#include <memory>

namespace rbc_ifem
{
  bool
  PositiveOrAuto::match(const std::string &text) const
  {
    if (Utilities::trim(text) == "auto")
      return true;
    try
      {
        std::size_t  end   = 0;
        const double value = std::stod(text, &end);
        return value > 0. && std::isfinite(value) &&
               Utilities::trim(text.substr(end)).empty();
      }
    catch (const std::exception &)
      {
        return false;
      }
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
} // namespace rbc_ifem
