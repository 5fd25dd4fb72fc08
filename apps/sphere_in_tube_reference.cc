/**
 * sphere-in-tube-reference: the body-fitted, axisymmetric reference for the
 * immersed sphere of doc/validation.md, Section 2. For a rigid sphere of
 * radius λR on the axis of a tube it prints, on a sequence of refined
 * meridian meshes, the towed drag factor K, the held drag factor and the
 * free sphere's U/U_c, as CSV on standard output.
 *
 *   sphere-in-tube-reference [LAMBDA [REFINEMENTS [HALF_LENGTH]]]
 *
 * LAMBDA = a/R (default 0.5), REFINEMENTS the finest global refinement
 * (default 4; the meshes 0 ... REFINEMENTS are all solved), HALF_LENGTH the
 * tube's half length in radii (default 4).
 */

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/reference/axisymmetric_sphere_in_tube.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  using namespace rbc_ifem;

  const char *const usage =
    "Usage: sphere-in-tube-reference [LAMBDA [REFINEMENTS [HALF_LENGTH]]]\n"
    "  LAMBDA       sphere radius over tube radius, in (0, 0.9] (default 0.5)\n"
    "  REFINEMENTS  finest global refinement of the meridian mesh, 0 ... 7 (default 4)\n"
    "  HALF_LENGTH  tube half length in tube radii, at least 2 (default 4)\n";

  /// The argument @p text as a number, or an InputError naming @p name.
  double
  number(const std::string &name, const std::string &text)
  {
    std::size_t used = 0;
    double      value;
    try
      {
        value = std::stod(text, &used);
      }
    catch (const std::exception &)
      {
        used = 0;
      }
    if (used == 0 || used != text.size())
      throw InputError(name, text, "a number");
    return value;
  }
} // namespace

int
main(int argc, char *argv[])
{
  const std::vector<std::string> arguments(argv + 1, argv + argc);
  if (!arguments.empty() && (arguments[0] == "--help" || arguments[0] == "-h"))
    {
      std::cout << usage;
      return 0;
    }
  try
    {
      if (arguments.size() > 3)
        throw InputError(
          "sphere-in-tube-reference takes at most three arguments");
      const double lambda =
        arguments.size() > 0 ? number("LAMBDA", arguments[0]) : 0.5;
      const double refinements =
        arguments.size() > 1 ? number("REFINEMENTS", arguments[1]) : 4;
      const double half_length =
        arguments.size() > 2 ? number("HALF_LENGTH", arguments[2]) : 4;
      if (!(refinements >= 0 && refinements <= 7 &&
            refinements == std::floor(refinements)))
        throw InputError("REFINEMENTS", arguments[1], "an integer from 0 to 7");
      // Checked here, before the first line of output.
      if (!(lambda > 0. && lambda <= 0.9))
        throw InputError("LAMBDA", arguments[0], "a radius ratio in (0, 0.9]");
      if (!(half_length >= 2.))
        throw InputError("HALF_LENGTH", arguments[2], "at least 2 tube radii");

      std::cout
        << "lambda,refinements,cells,dofs,towed_drag_factor,held_drag_factor,"
           "velocity_ratio,wall_seconds\n";
      for (unsigned int level = 0; level <= refinements; ++level)
        {
          const auto             start = std::chrono::steady_clock::now();
          const SphereInTubeDrag drag =
            axisymmetric_sphere_in_tube(lambda, level, half_length);
          const std::chrono::duration<double> seconds =
            std::chrono::steady_clock::now() - start;
          std::cout << lambda << ',' << level << ',' << drag.n_cells << ','
                    << drag.n_dofs << ',' << std::setprecision(10)
                    << drag.towed_drag_factor << ',' << drag.held_drag_factor
                    << ',' << drag.velocity_ratio << ',' << std::setprecision(3)
                    << seconds.count() << std::setprecision(6) << std::endl;
        }
    }
  catch (const InputError &e)
    {
      std::cerr << "sphere-in-tube-reference: error: " << e.what() << '\n'
                << usage;
      return 1;
    }
  catch (const std::exception &e)
    {
      std::cerr << "sphere-in-tube-reference: internal error: " << e.what()
                << std::endl;
      return 2;
    }
  return 0;
}
