#ifndef rbc_ifem_tests_membrane_fixtures_h
#define rbc_ifem_tests_membrane_fixtures_h

// What the membrane tests share: a random vector, its relative difference,
// the parameters with every energy term on, a membrane's response at a
// shape and the Evans-Fung cell.

#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/membrane/membrane.h>
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

  /// A membrane's energy, forces, and K v with its tangent stiffness K, at
  /// one shape.
  struct Response
  {
    double            energy = 0.;
    Vector<double>    forces;
    Vector<double>    Kv;
    MembraneStiffness K;
  };

  /// The Response of @p membrane at @p x, with K times @p v.
  inline Response
  respond(const Membrane       &membrane,
          const Vector<double> &x,
          const Vector<double> &v)
  {
    Response response;
    response.forces.reinit(x.size());
    response.Kv.reinit(x.size());
    response.energy = membrane.energy_and_forces(x, response.forces).total();
    membrane.stiffness(x, response.K);
    response.K.vmult_add(response.Kv, v);
    return response;
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
