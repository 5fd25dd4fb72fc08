// Every parameter's allowed text (what --print-parameters and parameters.prm
// print after "Allowed:", and what a refused value's message says is
// allowed) agrees with what the program accepts, at both ends of each
// numeric range: for "a number ≥ L" the value L runs and a value below it is
// refused; for "a number > L" L is refused and a value just above runs; for
// an upper bound U the same from above. "Runs" means RunParameters::read()
// (the patterns, then every validate()) throws no InputError, with the
// parameter changed by --set and everything else at its default, under the
// experiment whose own subsection holds it (else the default experiment).
// Bounds that depend on another parameter are not in the allowed text and
// are listed below with the reason; a listed bound that no longer fails
// fails the test too, so the list stays true.

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/experiments/registry.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>

using namespace rbc_ifem;

namespace
{
  /// A numeric range read from an allowed text.
  struct Range
  {
    bool                  whole = false;
    std::optional<double> lower, upper;
    bool                  strict_lower = false;
    unsigned int          list_length  = 0; // 0: a single value
  };

  /// The range an allowed text states, if it states one.
  std::optional<Range>
  range_of(const std::string &allowed)
  {
    static const std::regex list(
      R"(a list of exactly (\d+) items separated by '(.)', each (.*))");
    static const std::regex open_list(
      R"(a list of (?:one or more|any number of) items separated by '(.)', each (.*))");
    static const std::regex at_least(R"(a (whole )?number ≥ (\S+))");
    static const std::regex above(
      R"(a (whole )?number > (\S+)(?: and ≤ (\S+))?(, or auto)?)");
    static const std::regex between(R"(a (whole )?number from (\S+) to (\S+))");
    std::smatch             m;
    if (std::regex_match(allowed, m, list) ||
        std::regex_match(allowed, m, open_list))
      {
        const bool fixed = m.size() == 4;
        auto       range = range_of(m[fixed ? 3 : 2]);
        if (range)
          range->list_length = fixed ? std::stoul(m[1]) : 1;
        return range;
      }
    Range range;
    if (std::regex_match(allowed, m, at_least))
      range.lower = std::stod(m[2]);
    else if (std::regex_match(allowed, m, above))
      {
        range.lower        = std::stod(m[2]);
        range.strict_lower = true;
        if (m[3].matched)
          range.upper = std::stod(m[3]);
      }
    else if (std::regex_match(allowed, m, between))
      {
        range.lower = std::stod(m[2]);
        range.upper = std::stod(m[3]);
      }
    else
      return std::nullopt;
    range.whole = m[1].matched;
    return range;
  }

  /// The values at both ends of @p range, each with whether the range
  /// allows it: a bound and the value a step beyond it.
  std::vector<std::pair<double, bool>>
  probes(const Range &range)
  {
    const double                         step = range.whole ? 1. : 1e-3;
    std::vector<std::pair<double, bool>> values;
    if (range.lower)
      {
        values.emplace_back(*range.lower, !range.strict_lower);
        values.emplace_back(range.strict_lower ? *range.lower + step :
                                                 *range.lower - step,
                            range.strict_lower);
      }
    if (range.upper)
      {
        values.emplace_back(*range.upper, true);
        values.emplace_back(*range.upper + step, false);
      }
    return values;
  }

  /// @p value as --set gives it, repeated for a list.
  std::string
  value_text(const double value, const Range &range)
  {
    std::ostringstream s;
    s.precision(12);
    for (unsigned int i = 0; i < std::max(1u, range.list_length); ++i)
      s << (i > 0 ? ", " : "") << value;
    return s.str();
  }

  /**
   * What an experiment needs besides its defaults to be valid: the shear
   * box is a multiple of the capsule's diameter, the finite uptake and the
   * flowing layouts need cut cells, DM solves and a given time step, the
   * transit (for now) cells held in place. (That an
   * experiment's defaults alone do not run is issue 50's.)
   */
  std::string
  baseline(const std::string &experiment)
  {
    if (experiment == "shear")
      return "subsection Cells\n set Diameter = 6\nend\n";
    if (experiment == "finite uptake")
      return "subsection Diffusion\n set Method = cut cell\nend\n";
    if (experiment == "transit")
      return "subsection Transit\n set Cells flow = false\nend\n";
    if (experiment == "flowing layouts")
      return "subsection Immersed cells\n set Diffusion interval = 1\nend\n"
             "subsection Time\n set Time step = 3e-4\nend\n";
    return "";
  }

  /// The InputError message of a run of @p experiment with @p change, or
  /// "" if it reads and validates.
  std::string
  refusal(const std::string &experiment, const std::string &change)
  {
    const std::string file = "allowed_values.prm";
    std::ofstream(file) << "set Experiment = " << experiment << '\n'
                        << baseline(experiment);
    try
      {
        RunParameters run;
        run.read(file, {change});
        return "";
      }
    catch (const InputError &e)
      {
        return e.what();
      }
  }

  /// "Subsection/.../Entry" -> the experiment whose own subsection holds it.
  std::map<std::string, std::string>
  owners()
  {
    std::map<std::string, std::string> owner;
    for (const ExperimentType &type : experiment_types())
      if (type.make_parameters)
        {
          ParameterHandler prm;
          auto             own = type.make_parameters();
          own->add_parameters(prm);
          for (const auto &[path, pattern] : parameter_patterns(prm))
            owner[path] = type.name;
        }
    return owner;
  }

  /**
   * The bounds of the allowed text that another parameter's value moves:
   * "path at value" -> why its check refuses a value the text allows.
   */
  const std::map<std::string, std::string> &
  cross_checks()
  {
    static const std::map<std::string, std::string> list{
      {"Membrane/Area dilation modulus at 0",
       "the neo-Hookean law needs K >= 3 G, the Skalak law K > G"},
      {"Shear/Box size at 0.001, 0.001, 0.001",
       "each side a multiple of Cells/Diameter, at least twice it"},
      {"Cells/Diameter at 0.001",
       "Cell interactions/Repulsion range (0.3 µm) must be below it"},
      {"Geometry/Capillary length at 0.001",
       "Cell interactions/Repulsion range must be below half of it"},
      {"Geometry/Capillary radius at 0.001",
       "Cell interactions/Wall range (0.3 µm) must be below it"},
      {"Shear/Total strain at 0.001",
       "Shear/Averaging strain (0.5) must be below it"},
      {"Transit/Duration at 0.001",
       "at least one Transit/Time step (0.002 s)"}};
    return list;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;
  RunParameters                    defaults;
  const auto                       owner = owners();
  std::set<std::string>            cross_seen;
  unsigned int                     n_ranges = 0;

  for (const auto &[path, pattern] : parameter_patterns(defaults.handler()))
    {
      const std::string          allowed = allowed_values(pattern);
      const std::optional<Range> range   = range_of(allowed);
      if (!range)
        continue;
      ++n_ranges;
      const std::string experiment =
        owner.count(path) ? owner.at(path) : "flow";
      for (const auto &[value, allows] : probes(*range))
        {
          const std::string text = value_text(value, *range);
          const std::string why  = refusal(experiment, path + "=" + text);
          const std::string key  = path + " at " + text;
          if (allows && !why.empty() && cross_checks().count(key))
            {
              cross_seen.insert(key);
              continue;
            }
          check.holds(path + " = " + text +
                        (allows ? " runs (" : " is refused (") + allowed + ")" +
                        (why.empty() ? "" : ": " + why),
                      allows == why.empty());
        }
    }
  for (const auto &[key, reason] : cross_checks())
    check.holds("the listed cross check " + key + " still refuses (" + reason +
                  ")",
                cross_seen.count(key) > 0);
  check.at_least("parameters with a numeric range", n_ranges, 60);
  std::remove("allowed_values.prm");
  return check.exit_code();
}
