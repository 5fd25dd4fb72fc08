#ifndef rbc_ifem_tests_check_h
#define rbc_ifem_tests_check_h

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

/**
 * The assertions of rbc-ifem's numeric tests: each prints what it compared,
 * the numbers and the tolerance, and counts failures; a test's main()
 * returns exit_code(), so ctest fails if any check failed.
 */
class Checker
{
public:
  /// |value - expected| <= tolerance.
  void
  near(const std::string &what,
       const double       value,
       const double       expected,
       const double       tolerance)
  {
    report(what,
           std::abs(value - expected) <= tolerance,
           value,
           "expected " + number(expected) + " ± " + number(tolerance));
  }

  /// value <= bound.
  void
  at_most(const std::string &what, const double value, const double bound)
  {
    report(what, value <= bound, value, "bound <= " + number(bound));
  }

  /// value >= bound.
  void
  at_least(const std::string &what, const double value, const double bound)
  {
    report(what, value >= bound, value, "bound >= " + number(bound));
  }

  void
  holds(const std::string &what, const bool condition)
  {
    std::cout << (condition ? "  ok     " : "  FAILED ") << what << '\n';
    failures += !condition;
  }

  int
  exit_code() const
  {
    std::cout << (failures == 0 ? "all checks passed" :
                                  std::to_string(failures) + " check(s) FAILED")
              << std::endl;
    return failures == 0 ? 0 : 1;
  }

private:
  static std::string
  number(const double x)
  {
    std::ostringstream s;
    s << std::setprecision(6) << x;
    return s.str();
  }

  void
  report(const std::string &what,
         const bool         ok,
         const double       value,
         const std::string &criterion)
  {
    std::cout << (ok ? "  ok     " : "  FAILED ") << what << " = "
              << number(value) << " (" << criterion << ")\n";
    failures += !ok;
  }

  int failures = 0;
};

#endif
