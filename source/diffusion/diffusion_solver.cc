#include <rbc_ifem/base/output.h>
#include <rbc_ifem/diffusion/diffusion_solver.h>
#include <rbc_ifem/diffusion/end_periodicity.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/hp/fe_values.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rbc_ifem
{
  namespace
  {
    /**
     * -flux n on a membrane: the flux vector, pointing into the cell.
     * DataOut gives normals to postprocessors only on faces (DataOutFaces),
     * so they come from an FEValues at the patch points of each membrane
     * cell. Those are the (n+1)² points of a uniform grid on the unit cell,
     * in lexicographic order; taking them from there, rather than inverting
     * the map at the points DataOut hands over, also works on the cells that
     * a folded rim distorts, where the inversion fails.
     */
    class FluxVector : public DataPostprocessorVector<3>
    {
    public:
      FluxVector(const Mapping<2, 3> &mapping, const std::string &name)
        : DataPostprocessorVector<3>(name,
                                     update_values | update_quadrature_points)
        , mapping(mapping)
      {}

      void
      evaluate_scalar_field(
        const DataPostprocessorInputs::Scalar<3> &inputs,
        std::vector<Vector<double>>              &computed) const override
      {
        const auto         cell     = inputs.template get_cell<2>();
        const unsigned int n_points = inputs.evaluation_points.size();
        const unsigned int n =
          std::lround(std::sqrt(static_cast<double>(n_points))) - 1;
        AssertThrow(n >= 1 && (n + 1) * (n + 1) == n_points,
                    ExcInternalError());
        std::vector<Point<2>> unit_points;
        for (unsigned int j = 0; j <= n; ++j)
          for (unsigned int i = 0; i <= n; ++i)
            unit_points.emplace_back(static_cast<double>(i) / n,
                                     static_cast<double>(j) / n);
        FEValues<2, 3> fe_values(mapping,
                                 fe,
                                 Quadrature<2>(unit_points),
                                 update_normal_vectors |
                                   update_quadrature_points);
        fe_values.reinit(cell);
        for (unsigned int q = 0; q < n_points; ++q)
          {
            AssertThrow(fe_values.quadrature_point(q).distance(
                          inputs.evaluation_points[q]) <=
                          1e-8 * cell->diameter(),
                        ExcMessage("DataOut's patch points are not the "
                                   "lexicographic grid FluxVector assumes"));
            for (unsigned int d = 0; d < 3; ++d)
              computed[q](d) =
                -inputs.solution_values[q] * fe_values.normal_vector(q)[d];
          }
      }

    private:
      const Mapping<2, 3> &mapping;
      const FE_Q<2, 3>     fe{1};
    };
  } // namespace

  DiffusionSolver::DiffusionSolver(const double alveolar_pressure)
    : alveolar_pressure(alveolar_pressure)
  {}

  const std::vector<double> &
  DiffusionSolver::membrane_flows() const
  {
    return flows;
  }

  double
  DiffusionSolver::total_flow() const
  {
    return std::accumulate(flows.begin(), flows.end(), 0.);
  }

  double
  DiffusionSolver::flow_per_pressure() const
  {
    return total_flow() / alveolar_pressure;
  }

  SolverFailure
  DiffusionSolver::no_convergence(const std::string                  &solver,
                                  const SolverControl::NoConvergence &e,
                                  const double                        tolerance,
                                  const std::string                  &advice)
  {
    return SolverFailure(
      solver + " did not converge in " + std::to_string(e.last_step) +
      " iterations (residual " + Utilities::to_string(e.last_residual) +
      ", wanted " + Utilities::to_string(tolerance) + "). " + advice);
  }

  double
  DiffusionSolver::boundary_flow() const
  {
    return alveolar_flow;
  }

  unsigned int
  DiffusionSolver::n_iterations() const
  {
    return iterations;
  }

  double
  DiffusionSolver::flow_through_boundary(
    const DoFHandler<3>                       &dof_handler,
    const Mapping<3>                          &mapping,
    const TrilinosWrappers::MPI::Vector       &P,
    const types::boundary_id                   boundary,
    const std::function<double(unsigned int)> &permeability,
    const MPI_Comm                             communicator)
  {
    const auto   &fe_collection = dof_handler.get_fe_collection();
    ComponentMask first(fe_collection.n_components(), false);
    first.set(0, true);
    const FEValuesExtractors::Scalar pressure(0);
    const IndexSet                   boundary_dofs =
      DoFTools::extract_boundary_dofs(dof_handler, first, {boundary});
    hp::QCollection<3> quadrature;
    for (unsigned int i = 0; i < fe_collection.size(); ++i)
      quadrature.push_back(
        QGauss<3>(std::max(fe_collection[i].degree, 1u) + 1));
    const hp::MappingCollection<3>       mappings(mapping);
    hp::FEValues<3>                      hp_fe_values(mappings,
                                 fe_collection,
                                 quadrature,
                                 update_gradients | update_JxW_values);
    std::vector<Tensor<1, 3>>            gradients;
    std::vector<types::global_dof_index> dofs;
    double                               local_flow = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->get_fe().n_dofs_per_cell() > 0)
        {
          dofs.resize(cell->get_fe().n_dofs_per_cell());
          cell->get_dof_indices(dofs);
          if (std::none_of(dofs.begin(), dofs.end(), [&](const auto dof) {
                return boundary_dofs.is_element(dof);
              }))
            continue;
          hp_fe_values.reinit(cell);
          const FEValues<3> &fe_values = hp_fe_values.get_present_fe_values();
          gradients.resize(fe_values.n_quadrature_points);
          fe_values[pressure].get_function_gradients(P, gradients);
          const double alpha_D = permeability(cell->material_id());
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (boundary_dofs.is_element(dofs[i]))
              for (const unsigned int q : fe_values.quadrature_point_indices())
                local_flow += alpha_D * gradients[q] *
                              fe_values[pressure].gradient(i, q) *
                              fe_values.JxW(q);
        }
    return Utilities::MPI::sum(local_flow, communicator);
  }

  void
  DiffusionSolver::make_pressure_constraints(
    const DoFHandler<3>         &dof_handler,
    const Mapping<3>            &mapping,
    const types::boundary_id     pressure_boundary,
    const double                 pressure,
    const std::optional<double> &period,
    AffineConstraints<double>   &constraints,
    const IndexSet              &zero_dofs)
  {
    IndexSet relevant_dofs;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    constraints.clear();
    constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    for (const auto dof : zero_dofs)
      if (!constraints.is_constrained(dof))
        constraints.add_line(dof);
    const unsigned int n_components =
      dof_handler.get_fe_collection().n_components();
    ComponentMask first(n_components, false);
    first.set(0, true);
    VectorTools::interpolate_boundary_values(
      hp::MappingCollection<3>(mapping),
      dof_handler,
      pressure_boundary,
      Functions::ConstantFunction<3>(pressure, n_components),
      constraints,
      first);
    if (period)
      make_end_periodicity_constraints(dof_handler, constraints);
    // On a distributed mesh a ghost cell's nodes can hang on a cell this
    // rank does not see, and the cut cells' ghost penalty reaches across to
    // them: each such constraint comes from the rank that owns the node.
    if (dynamic_cast<const parallel::DistributedTriangulationBase<3> *>(
          &dof_handler.get_triangulation()) != nullptr)
      constraints.make_consistent_in_parallel(dof_handler.locally_owned_dofs(),
                                              relevant_dofs,
                                              dof_handler.get_communicator());
    constraints.close();
  }

  DiffusionSolver::OutputFiles
  DiffusionSolver::write_fields(
    const DataOut<3>                                     &data_out,
    const std::vector<const Triangulation<2, 3> *>       &membranes,
    const MappingQ<2, 3>                                 &mapping,
    const std::vector<std::unique_ptr<DoFHandler<2, 3>>> &dof_handlers,
    const std::vector<Vector<double>>                    &flux,
    const std::string                                    &directory,
    const std::string                                    &name,
    const unsigned int                                    counter,
    const MPI_Comm                                        communicator,
    const FieldData                                      &field_data,
    const std::string                                    &flux_name)
  {
    OutputFiles files;
    files.pressure = write_vtu_pieces(
      data_out, directory, name, counter, communicator, field_data);
    const FluxVector flux_vector(mapping, flux_name + "_vector");
    files.membranes = write_membranes(
      membranes,
      mapping,
      directory,
      name + "_membranes_" + Utilities::int_to_string(counter, 4),
      communicator,
      [&](const unsigned int m, DataOut<2, 3> &membrane_out) {
        membrane_out.add_data_vector(*dof_handlers[m], flux[m], flux_name);
        membrane_out.add_data_vector(*dof_handlers[m], flux[m], flux_vector);
      },
      field_data);
    return files;
  }
} // namespace rbc_ifem
