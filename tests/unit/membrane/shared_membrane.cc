// mpirun: 2 3

// A membrane whose work is shared out over the ranks (Membrane::share_work())
// gives every rank the energy, the forces and the products with the tangent
// stiffness of the same membrane working alone, to round-off: for both
// elastic laws and both element degrees, all energy terms on, at a randomly
// perturbed Evans-Fung cell. Runs on 2 and 3 ranks (an uneven share).

#include <rbc_ifem/membrane/membrane.h>

#include "check.h"
#include "membrane_fixtures.h"

using namespace rbc_ifem;
using test::create_cell;
using test::random_vector;
using test::relative_difference;

namespace
{
  void
  check_shared(Checker           &check,
               const std::string &law,
               const unsigned int degree)
  {
    Triangulation<2, 3> surface;
    create_cell(surface, 2);
    MembraneParameters parameters = test::every_term();
    parameters.law                = law;
    parameters.degree             = degree;
    const Membrane alone(surface, parameters);
    Membrane       shared(surface, parameters);
    shared.share_work(MPI_COMM_WORLD);

    // The same random numbers on every rank.
    std::mt19937   random(7);
    Vector<double> x = alone.reference_positions();
    x += random_vector(x.size(), 0.05, random);
    const Vector<double> v = random_vector(x.size(), 1., random);

    const test::Response     a        = test::respond(alone, x, v);
    const test::Response     s        = test::respond(shared, x, v);
    const MembraneStiffness &K_shared = s.K;

    const std::string name = law + " Q" + std::to_string(degree) + ": ";
    check.at_most(name + "energy, shared against alone (relative)",
                  std::abs(s.energy - a.energy) / a.energy,
                  1e-13);
    check.at_most(name + "forces, shared against alone (relative)",
                  relative_difference(s.forces, a.forces),
                  1e-12);
    check.at_most(name + "K v, shared against alone (relative)",
                  relative_difference(s.Kv, a.Kv),
                  1e-12);
    // Each rank holds only its share of K's sparse part: the share is a
    // real split, not a copy.
    unsigned int rows_held = 0;
    for (unsigned int i = 0; i < K_shared.local.m(); ++i)
      {
        double row_sum = 0.;
        for (auto entry = K_shared.local.begin(i);
             entry != K_shared.local.end(i);
             ++entry)
          row_sum += std::abs(entry->value());
        rows_held += row_sum > 0.;
      }
    check.holds(name + "each rank holds a part of the sparse stiffness",
                rows_held < K_shared.local.m());
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports
  Checker check;
  for (const std::string law : {"Skalak", "neo-Hookean"})
    for (const unsigned int degree : {1u, 2u})
      check_shared(check, law, degree);
  return check.exit_code();
}
