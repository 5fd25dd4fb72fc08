// Membranes made like another (the constructor's `like`): the cells of a
// population are one reference shape placed in many places, and share the
// first cell's numbering of DoFs and nodes and its stiffness pattern. A
// cell placed elsewhere and turned, made like the cell at the origin, has
// the energy, forces and products with the tangent stiffness of the same
// cell made alone, exactly, and its stiffness is built on the very
// sparsity pattern of the cell it was made like; a finer cell given the
// same `like` makes its own numbering (the DoFs differ) and is right too.

#include <rbc_ifem/membrane/membrane.h>

#include "check.h"
#include "membrane_fixtures.h"

#include <utility>

using namespace rbc_ifem;
using test::create_cell;
using test::random_vector;
using test::relative_difference;

namespace
{
  /// The Evans-Fung cell centred at (10, 3, -2), its axis along (1, 1, 0).
  void
  create_turned_cell(Triangulation<2, 3> &surface,
                     const unsigned int   refinements)
  {
    create_cell_surface(surface,
                        EvansFungShape(7.5),
                        CellPlacement{Point<3>(10., 3., -2.),
                                      Tensor<1, 3>({1., 1., 0.})},
                        refinements);
  }

  /// @p made_like and @p alone, the same membrane, give the same energy,
  /// forces and K v at one randomly perturbed shape; returns K of the first.
  MembraneStiffness
  check_same(Checker           &check,
             const std::string &name,
             const Membrane    &made_like,
             const Membrane    &alone)
  {
    std::mt19937   random(3);
    Vector<double> x = alone.reference_positions();
    x += random_vector(x.size(), 0.05, random);
    const Vector<double> v = random_vector(x.size(), 1., random);

    test::Response       like      = test::respond(made_like, x, v);
    const test::Response by_itself = test::respond(alone, x, v);

    check.near(name + ": reference positions, made like against alone",
               relative_difference(made_like.reference_positions(),
                                   alone.reference_positions()),
               0.,
               0.);
    check.near(name + ": energy, made like against alone",
               like.energy,
               by_itself.energy,
               0.);
    check.near(name + ": forces, made like against alone (relative)",
               relative_difference(like.forces, by_itself.forces),
               0.,
               0.);
    check.near(name + ": K v, made like against alone (relative)",
               relative_difference(like.Kv, by_itself.Kv),
               0.,
               0.);
    return std::move(like.K);
  }
} // namespace

int
main()
{
  const MembraneParameters parameters = test::every_term();

  Triangulation<2, 3> origin_surface, turned_surface, fine_surface;
  create_cell(origin_surface, 2);
  create_turned_cell(turned_surface, 2);
  create_turned_cell(fine_surface, 3);
  const Membrane origin(origin_surface, parameters);

  Checker              check;
  MembraneStiffness    K_origin;
  const Vector<double> X = origin.reference_positions();
  origin.stiffness(X, K_origin);

  const Membrane          turned(turned_surface, parameters, &origin);
  const Membrane          turned_alone(turned_surface, parameters);
  const MembraneStiffness K_turned =
    check_same(check, "turned cell", turned, turned_alone);
  check.holds("the turned cell's stiffness is built on the pattern of the "
              "cell it was made like",
              &K_turned.local.get_sparsity_pattern() ==
                &K_origin.local.get_sparsity_pattern());

  const Membrane          fine(fine_surface, parameters, &origin);
  const Membrane          fine_alone(fine_surface, parameters);
  const MembraneStiffness K_fine =
    check_same(check, "finer cell", fine, fine_alone);
  check.holds("the finer cell's stiffness has a pattern of its own",
              &K_fine.local.get_sparsity_pattern() !=
                &K_origin.local.get_sparsity_pattern());
  return check.exit_code();
}
