#include <rbc_ifem/base/input_error.h>

#include <sstream>

namespace rbc_ifem
{
  InputError::InputError(const std::string &message)
    : std::runtime_error(message)
  {}

  InputError::InputError(const std::string &parameter,
                         const std::string &value,
                         const std::string &allowed)
    : std::runtime_error("parameter '" + parameter + "' = '" + value +
                         "' is not allowed: " + allowed)
  {}

  std::string
  to_text(const double value)
  {
    std::ostringstream s;
    s << value;
    return s.str();
  }
} // namespace rbc_ifem
