#ifndef rbc_ifem_base_input_error_h
#define rbc_ifem_base_input_error_h

#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  /**
   * The one exception for bad user input: a missing file, an unknown or
   * malformed parameter, or a request that is physically impossible. main()
   * prints its message and exits with a non-zero status before anything is
   * written, so every check that can throw it runs before the output stage.
   */
  class InputError : public std::runtime_error
  {
  public:
    /// A free-form message, for errors that are not about one parameter.
    explicit InputError(const std::string &message);

    /**
     * The usual case: the parameter (as "Subsection/Name"), the value that
     * was given and a sentence that says what is allowed.
     */
    InputError(const std::string &parameter,
               const std::string &value,
               const std::string &allowed);
  };

  /// @p value as a message shows it (six significant digits).
  std::string
  to_text(const double value);
} // namespace rbc_ifem

#endif
