#ifndef rbc_ifem_fluid_fluid_vectors_h
#define rbc_ifem_fluid_fluid_vectors_h

#include <deal.II/lac/la_parallel_block_vector.h>
#include <deal.II/lac/la_parallel_vector.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * A field of the velocity space (FluidProblem::velocity_dof_handler()):
   * deal.II's distributed vector, with ghost entries where a rank's cells
   * need them. Load vectors of the immersed coupling are of this type.
   */
  using VelocityVector = LinearAlgebra::distributed::Vector<double>;

  /// A field of the pressure space (FluidProblem::pressure_dof_handler()).
  using PressureVector = LinearAlgebra::distributed::Vector<double>;

  /// The plasma's state (v, p): block 0 the velocity, block 1 the pressure.
  using FluidVector = LinearAlgebra::distributed::BlockVector<double>;
} // namespace rbc_ifem

#endif
