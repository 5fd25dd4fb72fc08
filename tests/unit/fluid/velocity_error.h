#ifndef rbc_ifem_tests_unit_fluid_velocity_error_h
#define rbc_ifem_tests_unit_fluid_velocity_error_h

#include <rbc_ifem/fluid/fluid_problem.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/numerics/vector_tools.h>

/// ‖v - v_exact‖_L2 of @p fluid's velocity, v_exact the first three
/// components of the (v, p) function @p exact.
inline double
velocity_l2_error(const rbc_ifem::FluidProblem &fluid,
                  const dealii::Function<3>    &exact)
{
  using namespace dealii;
  /// The velocity of a (v, p) function.
  class VelocityOf : public Function<3>
  {
  public:
    explicit VelocityOf(const Function<3> &flow)
      : Function<3>(3)
      , flow(flow)
    {}

    double
    value(const Point<3> &p, const unsigned int component) const override
    {
      return flow.value(p, component);
    }

  private:
    const Function<3> &flow;
  };

  const Triangulation<3> &mesh =
    fluid.velocity_dof_handler().get_triangulation();
  Vector<float> cellwise(mesh.n_active_cells());
  VectorTools::integrate_difference(fluid.get_mapping(),
                                    fluid.velocity_dof_handler(),
                                    fluid.solution().block(0),
                                    VelocityOf(exact),
                                    cellwise,
                                    QGauss<3>(5),
                                    VectorTools::L2_norm);
  return VectorTools::compute_global_error(mesh,
                                           cellwise,
                                           VectorTools::L2_norm);
}

#endif
