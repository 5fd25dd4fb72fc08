#ifndef rbc_ifem_tests_membrane_fixtures_h
#define rbc_ifem_tests_membrane_fixtures_h

// What the membrane tests share: a random vector, its relative difference,
// the parameters with every energy term on and the Evans-Fung cell.

#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/membrane/parameters.h>

#include <deal.II/lac/vector.h>

#include <random>

namespace rbc_ifem::test
{
  /// @p n entries uniform in [-amplitude, amplitude].
  inline Vector<double>
  random_vector(const unsigned int n,
                const double       amplitude,
                std::mt19937      &random)
  {
    std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
    Vector<double>                         v(n);
    for (auto &entry : v)
      entry = uniform(random);
    return v;
  }

  /// |a - b| / |b|
  inline double
  relative_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> difference(a);
    difference -= b;
    return difference.l2_norm() / b.l2_norm();
  }

  /// The default membrane with bending, area and volume penalties on.
  inline MembraneParameters
  every_term()
  {
    MembraneParameters parameters;
    parameters.bending_modulus = 0.2;
    parameters.area_penalty    = 500.;
    parameters.volume_penalty  = 500.;
    return parameters;
  }

  /// The Evans-Fung cell at the origin, axis z.
  inline void
  create_cell(Triangulation<2, 3> &surface, const unsigned int refinements)
  {
    create_cell_surface(surface,
                        EvansFungShape(7.5),
                        CellPlacement{Point<3>(), Tensor<1, 3>({0., 0., 1.})},
                        refinements);
  }
} // namespace rbc_ifem::test

#endif
